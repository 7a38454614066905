//! Dry contact of finite rollers and balls (thesis ch. 1): p >= 0, zero gap where p > 0, load balance.
