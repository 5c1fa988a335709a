"""The decks of `make bench`'s plastic comparison (visco2d.bench_plastic): the elastic twin is the
plastic apple without its PLASTIC card, its bruise a von Mises threshold at the yield stress, and
the no-bruise pair the same without a BRUISE card; every other card is the example's."""
import os

from visco2d import bench_plastic


def cards(path):
    with open(path) as handle:
        return [line for line in handle.read().splitlines() if line and not line.startswith("#")]


def test_twin_decks(tmp_path):
    os.makedirs(tmp_path / "decks")
    plastic, elastic, plastic_bare, elastic_bare = bench_plastic.decks(2, str(tmp_path))
    p, e, pb, eb = cards(plastic), cards(elastic), cards(plastic_bare), cards(elastic_bare)
    assert any(line.startswith("PLASTIC YIELD=0.3e6") for line in p)
    assert not any(line.startswith("PLASTIC") for line in e + eb)
    assert "MESH SPHERE R=0.03585 LEVEL=2" in p and "MESH SPHERE R=0.03585 LEVEL=2" in e
    assert [line for line in e if line.startswith("BRUISE")] == ["BRUISE CRITERION=MISES STRESS=0.3e6"]
    assert not any(line.startswith("BRUISE") for line in pb + eb)
    rest = [line for line in p if not line.startswith(("PLASTIC", "BRUISE"))]
    assert rest == [line for line in e if not line.startswith("BRUISE")]
    assert rest == [line for line in pb if not line.startswith("PLASTIC")] == eb
