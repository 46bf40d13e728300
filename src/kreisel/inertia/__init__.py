"""Mass properties (seed 四.1–3)."""

__all__ = ["RigidBody"]


class RigidBody:  # replaced by the mass-properties issue
    pass
