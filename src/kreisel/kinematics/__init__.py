"""kinematics layer of kreisel."""

__all__ = []
