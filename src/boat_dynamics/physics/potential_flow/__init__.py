"""Linear potential flow: a hull's coefficients, radiation, diffraction, speed terms."""
