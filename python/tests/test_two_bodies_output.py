"""results.h5 and results.xmf of a run with a second body (BODY card, doc/two_bodies.md): both meshes,
told apart by /mesh/node_body and /mesh/element_body (doc/outputs.md). Two level-1 spheres (106 nodes,
88 elements each), 0.2 ms: well under a second."""
import os
import subprocess

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXE = os.path.join(ROOT, "build", "install", "bin", "visco2d")

h5py = pytest.importorskip("h5py")
numpy = pytest.importorskip("numpy")
pytestmark = pytest.mark.skipif(not os.access(EXE, os.X_OK), reason="no visco2d executable (make build)")

DECK = """TITLE two level-1 spheres head on
ANALYSIS DYNAMIC
GEOMETRY AXISYMMETRIC
MATERIAL apple ELASTIC E=18.11e6 NU=0.219 RHO=756.85
MATERIAL peach ELASTIC E=10e6 NU=0.3 RHO=950
MESH SPHERE R=0.0366 LEVEL=1 MAT=apple
INITIAL VZ=-0.6
BODY SPHERE R=0.025 LEVEL=1 MAT=peach VZ=0.4
TIME DT=1e-5 TEND=2e-4
OUTPUT EVERY=10 FIELDS=0,1e-4
END
"""


@pytest.fixture(scope="module")
def case_folder(tmp_path_factory):
    folder = tmp_path_factory.mktemp("two_bodies")
    deck = folder / "pair.inp"
    deck.write_text(DECK)
    subprocess.run([EXE, "-q", "-o", str(folder / "out"), str(deck)], check=True, timeout=120)
    return folder / "out" / "pair"


def test_both_meshes_and_their_body_index(case_folder):
    with h5py.File(case_folder / "results.h5", "r") as results:
        nodes = results["/mesh/nodes"][()]
        elements = results["/mesh/elements"][()]
        node_body = results["/mesh/node_body"][()]
        element_body = results["/mesh/element_body"][()]
        assert nodes.shape == (212, 2) and elements.shape == (176, 4)
        assert node_body.shape == (212,) and element_body.shape == (176,)
        assert list(numpy.bincount(node_body)[1:]) == [106, 106]
        assert list(numpy.bincount(element_body)[1:]) == [88, 88]
        # each element's nodes belong to its own body
        assert (node_body[elements - 1] == element_body[:, None]).all()
        # the second body lies under the first: its highest node at the first's lowest (GAP=0)
        assert nodes[node_body == 2, 1].max() == pytest.approx(nodes[node_body == 1, 1].min(), abs=1e-12)
        # fields on every node; at t = 0 each body moves at its own velocity
        first = sorted(results["/fields"].keys())[0]
        velocity = results["/fields/" + first + "/velocity"][()]
        assert velocity.shape == (212, 2)
        assert numpy.allclose(velocity[node_body == 1, 1], -0.6)
        assert numpy.allclose(velocity[node_body == 2, 1], 0.4)


def test_xdmf_shows_the_body_index(case_folder):
    text = (case_folder / "results.xmf").read_text()
    assert 'Name="body"' in text and "/mesh/element_body" in text
    assert 'Name="node_body"' in text and "/mesh/node_body" in text
