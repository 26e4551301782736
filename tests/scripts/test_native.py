"""Which built FMU library a scene gets (python/rigidfmu/native.py): its own module
combination where the build has it, else the built superset with the fewest modules (a
build of the top combination only, as the sanitizer's, RIGIDFMU_VARIANTS=top)."""
import pytest

from rigidfmu.errors import NativeError
from rigidfmu.native import Native

FULL = [0, 2, 5, 7]
# with a fourth module bit (8), as the joints will add
WITH_JOINTS = FULL + [8, 10, 13, 15]


def native_with(tmp_path, masks, fmi=2):
    for mask in masks:
        (tmp_path / f"rigidfmu_fmi{fmi}_{mask}.so").write_bytes(b"")
    return Native(tmp_path)


@pytest.mark.parametrize("needed", FULL)
def test_a_full_build_gives_each_scene_its_own_combination(tmp_path, needed):
    assert native_with(tmp_path, FULL).variant(str(needed)) == str(needed)


@pytest.mark.parametrize("needed", FULL)
def test_a_build_of_the_top_combination_gives_it_to_every_scene(tmp_path, needed):
    assert native_with(tmp_path, [7]).variant(str(needed)) == "7"


@pytest.mark.parametrize("needed,chosen", [(0, 0), (2, 2), (5, 5), (8, 8), (10, 10), (13, 13), (15, 15)])
def test_more_modules_more_combinations(tmp_path, needed, chosen):
    assert native_with(tmp_path, WITH_JOINTS).variant(str(needed)) == str(chosen)


def test_the_superset_with_the_fewest_modules(tmp_path):
    native = native_with(tmp_path, [2, 7, 10, 15])
    assert native.variant("0") == "2"
    assert native.variant("5") == "7"
    assert native.variant("8") == "10"
    assert native.variant("13") == "15"


def test_each_fmi_version_has_its_own_libraries(tmp_path):
    native_with(tmp_path, [0], fmi=3)
    native = native_with(tmp_path, [7], fmi=2)
    assert native.built_variants(2) == [7] and native.built_variants(3) == [0]
    assert native.variant("0", 2) == "7" and native.variant("0", 3) == "0"


def test_no_library_with_the_modules_is_refused(tmp_path):
    (tmp_path / "rigidfmu_fmi2_x.so").write_bytes(b"")  # not a module mask: ignored
    native = native_with(tmp_path, [0, 2])
    with pytest.raises(NativeError, match="has the modules 5"):
        native.variant("5")
