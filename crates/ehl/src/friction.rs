//! Shear stress at the surfaces (thesis eq. 3.8) and the friction integral (eq. 3.5, 3.9, 3.10).
