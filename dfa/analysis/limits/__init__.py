"""Stiffness limits: the closed-form bounds, K_max four ways, the stiffness–speed chart and the Z-width."""
