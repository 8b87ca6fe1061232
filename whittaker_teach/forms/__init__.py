"""The classical equations of motion of a non-holonomic system, one module per form.

Every form is built on one :class:`NonholonomicSystem` (a Lagrangian and linear or
Chetaev constraints, of Chaplygin type or not) and gives its steps (labels in
square brackets: they are the course's, not Mei's) and the accelerations of the
independent coordinates.  :func:`agree` checks every form against every other at
random admissible points, in 40-digit arithmetic.

==========================  ===========================================================
:class:`RouthVoss`          Lagrange's equations with multipliers (Routh 1884, Voss 1885)
:class:`Voronets`           dependent coordinates kept (Voronets 1901); Chaplygin (1897)
                            (Mei's (1.4)) where it applies
:class:`Maggi`              the projection on the independent virtual displacements (1896)
:class:`GibbsAppell`        the acceleration energy S (Gibbs 1879, Appell 1899), from T or
                            (``via="bodies"``) from the bodies of a mechanics model
:class:`BoltzmannHamel`     quasi-velocities, Hamel's coefficients (Boltzmann 1902, Hamel 1904)
:class:`Kane`               generalized speeds and partial velocities (Kane 1961/1985), in
                            the Lagrangian setting or (``via="KanesMethod"``) through sympy
:class:`Nielsen`            dT/dt differentiated in the velocities (Nielsen 1935)
:class:`Tzenoff`            d^2T/dt^2 differentiated in the accelerations (Tzenoff 1924)
:func:`frobenius`           integrability of linear constraints (Frobenius 1877)
:func:`chetaev`             Chetaev's virtual displacements and the constraint force (1932-33)
==========================  ===========================================================

A system comes from a Lagrangian and its constraints, or from a
``sympy.physics.mechanics`` model (:func:`from_mechanics`: LagrangesMethod,
KanesMethod, System).  :func:`frobenius` decides whether linear constraints are
integrable; :func:`chetaev` shows Chetaev's virtual displacements and the constraint
force.  ``python -m whittaker_teach.forms.bench`` prints each form's cost on the chain of
sleighs beside LagrangesMethod and KanesMethod.  The core (``whittaker_teach/*.py``)
never imports this subpackage.

>>> from whittaker_teach.forms import examples, agree
>>> print(agree(examples.sledge(), forms=["RouthVoss", "Maggi"]).ok)
True
"""

from importlib import import_module

__all__ = ["NonholonomicSystem", "from_mechanics", "RouthVoss", "Voronets", "Maggi",
           "GibbsAppell", "BoltzmannHamel", "Kane", "Nielsen", "Tzenoff", "agree",
           "frobenius", "Integrability", "chetaev", "examples", "FORMS"]

_LAZY = {
    "NonholonomicSystem": ("model", "NonholonomicSystem"),
    "from_mechanics": ("model", "from_mechanics"),
    "RouthVoss": ("routh_voss", "RouthVoss"),
    "Voronets": ("voronets", "Voronets"),
    "Maggi": ("maggi", "Maggi"),
    "GibbsAppell": ("gibbs_appell", "GibbsAppell"),
    "BoltzmannHamel": ("boltzmann_hamel", "BoltzmannHamel"),
    "Kane": ("kane", "Kane"),
    "Nielsen": ("nielsen", "Nielsen"),
    "Tzenoff": ("nielsen", "Tzenoff"),
    "agree": ("compare", "agree"),
    "FORMS": ("compare", "FORMS"),
    "frobenius": ("integrability", "frobenius"),
    "Integrability": ("integrability", "Integrability"),
    "chetaev": ("chetaev", "chetaev"),
    "examples": ("examples", None),
}


def __getattr__(name):
    if name in _LAZY:
        module, attr = _LAZY[name]
        mod = import_module(f".{module}", __name__)
        value = mod if attr is None else getattr(mod, attr)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'whittaker_teach.forms' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(__all__))
