"""What the readers of model files (lagmb.urdf, lagmb.mjcf) share: the
largest number a model may hold, lagmb's one namespace for a file's names,
and the contact law a loaded model's contacts start from.
"""

import warnings

#: The largest mass (kg), length (m), moment of inertia (kg m^2), joint value,
#: mimic multiplier or offset, damping or friction a model may hold: lagmb
#: squares them (norms of constraint rows, the parallel-axis term m d^2), and
#: past about 1e154 a square overflows a double; 1e150 leaves room for sums.
LARGEST = 1e150

#: The contact between the ground and each collision shape that
#: load_urdf(ground=z) adds, unless ``contact`` says otherwise: a stiffness
#: that lets a 12 kg quadruped on four 2 cm feet sink 0.2 mm, restitution
#: 0.5 and friction 0.8 (rubber on a floor). load_mjcf's contacts start
#: from it too (``mb.urdf.GROUND_CONTACT``, as users know it).
GROUND_CONTACT = {"stiffness": 1e7, "restitution": 0.5, "friction": 0.8}


class Namespace:
    """lagmb's one namespace for the names of a file that keeps several
    (URDF: links and joints; MJCF: bodies, joints and equalities) and for
    the names lagmb makes (NAME_limit): a name is kept while free, else a
    file's element gets its kind added (NAME_joint), then a number
    (NAME_joint_2, ...; NAME_limit_2 for a made name), first claimed first
    served. Each change is listed in `renamed` for a warning, but for the
    documented one (`quiet`: a joint named like a link or body is
    NAME_joint)."""

    def __init__(self):
        self.holder = {"ground": ("ground", "the ground")}
        self.renamed = []

    def claim(self, wanted, kind, what, quiet=(), made=False):
        """The model's name for `what` ("joint 'arm'", of `kind` "joint"),
        which the file (or lagmb, `made`) calls `wanted`; `quiet`: the
        kinds whose holding `wanted` makes NAME_KIND without a warning."""
        name = wanted
        if name in self.holder and not made:
            name = f"{wanted}_{kind}"
        base, k = name, 2
        while name in self.holder:
            name, k = f"{base}_{k}", k + 1
        if name != wanted and not (name == f"{wanted}_{kind}" and self.holder[wanted][0] in quiet):
            self.renamed.append(f"{what} is '{name}' ({self.holder[wanted][1]} has the name '{wanted}')")
        self.holder[name] = (kind, what)
        return name

    def warn(self, path, category):
        if self.renamed:
            warnings.warn(category(f"{path}: lagmb keeps one namespace for all names, so: " +
                                   "; ".join(self.renamed)), stacklevel=3)
