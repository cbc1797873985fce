"""The names of a model's coordinates q: one function in the core
(lagmb/model/coordinates.hpp) gives them to Model.coordinate_names,
linearize's outputs, the FMU's variables and the core's messages; these
are the names each gave before it was one (issue 40)."""

import os

import lagmb as mb
from builders import ARM_URDF, pendulum

from paths import ROOT  # noqa: E402


def test_a_planar_body_has_x_y_angle_and_a_particle_x_y():
    model = pendulum()
    model.add_particle("bob", mass=0.5, position=(2.0, 0.0))
    model.add_distance("string", "rod", (1.0, 0.0), "bob", (2.0, 0.0))
    assert model.coordinate_names == ["rod.x", "rod.y", "rod.angle", "bob.x", "bob.y"]


def test_a_spatial_body_has_its_position_and_euler_parameters():
    model = mb.Model(dimension=3)
    model.add_body("base", mass=1.0, inertia=(0.1, 0.1, 0.1), position=(0.0, 0.0, 1.0))
    model.add_body("arm", mass=1.0, inertia=(0.1, 0.1, 0.1), position=(0.5, 0.0, 1.0))
    model.add_revolute("hinge", "base", "arm", at=(0.25, 0.0, 1.0), axis=(0.0, 1.0, 0.0))
    assert model.coordinate_names == [f"{b}.{c}" for b in ("base", "arm")
                                        for c in ("x", "y", "z", "e0", "e1", "e2", "e3")]


def test_a_robot_from_urdf_names_its_links(tmp_path):
    path = tmp_path / "arm.urdf"
    path.write_text(ARM_URDF)
    model = mb.load_urdf(path, limits=False)
    assert model.coordinate_names == ["upper." + c for c in ("x", "y", "z", "e0", "e1", "e2", "e3")]


def test_the_fmu_and_linearize_name_the_coordinates_alike():
    scene = mb.load_scene(os.path.join(ROOT, "examples", "slider_crank.toml"))
    names = scene.model.coordinate_names
    assert names[:3] == ["crank.x", "crank.y", "crank.angle"]
    from lagmb.fmu import setup_text

    variables = mb._core.CoSimulation(setup_text(scene)).variables
    assert [v["name"] for v in variables if v["description"].startswith("coordinate of body")] == names
    linear = mb.linearize(pendulum(), outputs=["rod.angle", "der(rod.x)"])
    assert list(linear.outputs) == ["rod.angle", "der(rod.x)"]
