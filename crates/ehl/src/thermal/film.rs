//! The energy equation across the film and the generalized Reynolds coefficients (to be built).
