//! Analytic and classical reference results used by `ehl check` and the tests (Hertz, Moes, Pan-Hamrock, Hamrock-Dowson, Palmgren).
