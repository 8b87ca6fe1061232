"""Built-in systems, each built on demand (importing this module builds none).

==================  ============================================================
``sledge()``        Mei's section 3: a sledge with a torsional spring (non-holonomic);
                    ``section3()`` derives and checks (3.1)-(3.15)
``projectile()``    a projectile in a vertical plane (holonomic; the path is a parabola)
``kepler()``        a particle in an inverse-square field (holonomic; the orbit is a conic)
``offset_sleigh()`` the Chaplygin sleigh, centre of mass at a distance b from the contact
``rolling_disk()``  a vertical disk rolling without slipping, with a heading spring
``cone_particle()`` a particle with the nonlinear constraint zdot = a sqrt(xdot^2 + ydot^2)
``charged_particle()`` a charge in a magnetic field (holonomic, a term linear in velocities)
==================  ============================================================

>>> from whittaker_teach import examples
>>> [e.name for e in examples.catalogue()][:3]
['sledge', 'projectile', 'kepler']
"""

from dataclasses import dataclass

from ._charged import charged_particle
from ._cone import cone_particle
from ._disk import rolling_disk
from ._exact import sledge_exact
from ._kepler import kepler
from ._projectile import projectile
from ._sledge import section3, sledge
from ._sleigh import offset_sleigh

__all__ = ["sledge", "section3", "projectile", "kepler", "offset_sleigh", "rolling_disk", "cone_particle",
           "charged_particle", "catalogue", "get", "Example", "sledge_exact"]


@dataclass(frozen=True)
class Example:
    """A built-in system: its name, a description, and the reduction the book uses."""

    name: str
    description: str
    coordinate: str
    direction: int = 1

    def build(self):
        """Build the system (a ChaplyginSystem)."""
        return globals()[self.name]()

    def reduce(self):
        """Build the system and reduce it with the default q_eps and direction."""
        return self.build().reduce(self.coordinate, self.direction)


_CATALOGUE = [
    Example("sledge", "Mei's section 3: a sledge with a torsional spring", "x"),
    Example("projectile", "a projectile; the path y(x) is a parabola", "x"),
    Example("kepler", "the Kepler problem; the orbit r(theta) is a conic", "theta"),
    Example("offset_sleigh", "the Chaplygin sleigh, centre of mass off the contact "
            "point", "x"),
    Example("rolling_disk", "a vertical disk rolling without slipping", "theta"),
    Example("cone_particle", "a nonlinear constraint zdot = a sqrt(xdot^2 + ydot^2)",
            "x"),
    Example("charged_particle", "a charge in a magnetic field (gyroscopic term)",
            "x"),
]


def catalogue():
    """The built-in examples, as :class:`Example` records."""
    return list(_CATALOGUE)


def get(name):
    """The :class:`Example` called ``name``; ModelError if there is none."""
    for e in _CATALOGUE:
        if e.name == name:
            return e
    from ..errors import ModelError
    raise ModelError(f"no built-in example {name!r}; the examples are "
                     f"{', '.join(e.name for e in _CATALOGUE)}")


