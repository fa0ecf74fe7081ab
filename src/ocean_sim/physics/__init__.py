"""The pure ocean core: Gerstner waves, spectra and physical constants (numpy only)."""

__all__: list[str] = []
