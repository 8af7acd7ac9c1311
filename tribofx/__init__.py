"""tribofx: finite wear and soft-EHL of soft solids at finite deformation on FEniCSx."""

__all__ = ["__version__"]
__version__ = "0.1.0"
