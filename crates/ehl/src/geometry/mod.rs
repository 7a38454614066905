//! Gap of the undeformed bodies g(x, y): roller profiles, misalignment, unequal radii, balls.
