"""The benchmark's wide pile differs from the cube-root piles in its layout only, so that
the growth it measures from the pile of 100 is that of N at equal height (bench.py's
"Equal height" rows)."""
from rigidfmu.scenes import bench


def _without(body, *keys):
    return {k: v for k, v in body.items() if k not in keys}


def test_wide_pile_is_the_pile_of_100_on_a_wider_grid():
    wide, small = bench.pile_wide_scene(bench.WIDE_PILE), bench.pile_manifold_scene(100)
    assert len(wide["bodies"]) == bench.WIDE_PILE
    # the same cubes (shape, mass, friction, restitution), floor, step and solver
    assert {str(_without(b, "name", "position", "orientation")) for b in wide["bodies"]} == \
        {str(_without(small["bodies"][0], "name", "position", "orientation"))}
    assert wide["surfaces"] == small["surfaces"] and wide["solver"] == small["solver"]
    # columns as tall as the pile of 100's: 4 layers, 16 x 16 columns (5 x 5 for 100)
    for scene, layers, side in ((wide, bench.WIDE_LAYERS, 16), (small, 4, 5)):
        z = {round(b["position"][2], 9) for b in scene["bodies"]}
        xy = {(round(b["position"][0], 9), round(b["position"][1], 9)) for b in scene["bodies"]}
        assert len(z) == layers and len(xy) == side * side


def test_columns_of_four_lay_out_the_pile_of_100_as_before():
    assert bench.pile_layout(100, layers=4) == bench.pile_layout(100)
    assert len({round(p[2], 9) for p, _ in bench.pile_layout(1000)}) == 10  # the tall pile: columns of 10


def test_soft_pile_differs_from_the_manifold_pile_in_its_solver_only():
    soft, manifold = bench.pile_soft_scene(100), bench.pile_manifold_scene(100)
    assert soft["solver"] == dict(manifold["solver"], contacts="soft")
    assert soft["bodies"] == manifold["bodies"] and soft["surfaces"] == manifold["surfaces"]
