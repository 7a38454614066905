//! EHL coupling: film h = h0 + g + deflection (thesis eq. 2.3), load balance through h0, steady drivers.
