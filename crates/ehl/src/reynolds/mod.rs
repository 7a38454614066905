//! The discrete Reynolds equation (thesis eq. 2.1, 3.1) and its solvers.
