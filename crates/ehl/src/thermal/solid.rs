//! The surface temperature of a body moving under a heat flux (to be built).
