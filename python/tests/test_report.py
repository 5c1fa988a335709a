"""visco2d.report's pure parts: the wrapped title and the elements outside the assessed flesh."""
import numpy as np

from visco2d import report


def test_long_names_wrap_at_separators():
    name = "peach_drop_" + "_".join(["station"] * 30)
    lines = report.title_lines(name + ": a title", "DYNAMIC axisymmetric", "/tmp/" + "/".join(["deep"] * 40) + "/results.h5",
                               width=60)
    for line in lines.split("\n"):
        assert len(line) <= 60
    assert lines.replace("\n", "").replace(" ", "") == (name + ":atitle" + "DYNAMICaxisymmetric(/tmp/"
                                                         + "/".join(["deep"] * 40) + "/results.h5)")
    assert lines.split("\n")[0].endswith("_")          # cut after a separator, not inside a word


def test_short_title_unchanged():
    assert report.title_lines("a: b", "c", "d") == "a: b\nc\n(d)"


def fake_case(threshold):
    nelem = len(threshold)
    envelope = np.arange(nelem * 4, dtype=float).reshape(nelem, 4)
    elements = np.array([[k, k + 1, k + 2, k + 3] for k in range(nelem)])
    nodes = np.zeros((nelem + 3, 2))
    return {"path": "x", "summary": {"pad_compression_max_mm": "1.0", "bruise_criterion": "MAXSHEAR"},
            "nodes": nodes, "elements": elements, "geometry": "AXISYMMETRIC",
            "bruise": {"max_shear_envelope": envelope, "max_shear_envelope_nodal": np.zeros(nelem + 3),
                       "threshold": np.asarray(threshold, float),
                       "gauss_r": envelope * 0.0, "gauss_z": envelope * 0.0,
                       "bruised": np.zeros_like(envelope)}}


def test_pad_elements_outside_and_not_the_maximum():
    threshold = [[3e5] * 4, [3e5] * 4, [0.0] * 4]          # the third element is the pad's
    data = report.envelope_data(fake_case(threshold))
    assert data["outside"].tolist() == [False, False, True]
    assert data["outside_label"].startswith("pad")
    assert data["peak"][2] == 7.0 * 1e-6                     # element 2's last point (MPa), not the pad's 11


def test_nothing_outside_without_any_assessment():
    data = report.envelope_data(fake_case([[0.0] * 4] * 3))
    assert not data["outside"].any()


def test_plastic_criterion_draws_the_plastic_strain():
    """BRUISE CRITERION=PLASTIC: the field is /bruise/equivalent_plastic_strain (in %), the flesh assessed
    is /bruise/assessed even at STRAIN=0 (threshold 0), and the region is outlined from the bruised points."""
    nelem = 3
    strain = np.array([[0.0, 0.01, 0.02, 0.03], [0.0] * 4, [0.05, 0.0, 0.0, 0.0]])
    elements = np.array([[k, k + 1, k + 2, k + 3] for k in range(nelem)])
    case = {"path": "x", "summary": {"bruise_criterion": "PLASTIC", "bruise_threshold_strain": 0.0,
                                     "plastic_dissipation_J": 0.153, "equivalent_plastic_strain_max": 0.05,
                                     "residual_flattening_mm": 1.15},
            "nodes": np.zeros((nelem + 3, 2)), "elements": elements, "geometry": "AXISYMMETRIC",
            "bruise": {"equivalent_plastic_strain": strain,
                       "equivalent_plastic_strain_nodal": np.linspace(0.0, 0.05, nelem + 3),
                       "threshold": np.zeros_like(strain), "assessed": np.ones_like(strain),
                       "gauss_r": np.ones_like(strain), "gauss_z": np.ones_like(strain),
                       "bruised": (strain > 0.0).astype(float)}}
    data = report.envelope_data(case)
    assert data["measure"] == "equivalent_plastic_strain" and data["unit"] == "%"
    assert data["peak"][2] == 100.0 * 0.05                   # element 3's first point, in %
    assert not data["outside"].any()                         # threshold 0, yet all the flesh is assessed
    assert data["threshold"] is None                         # no line on the colour bar at 0 %
    assert data["mixed"]                                     # outlined from the bruised Gauss points
    assert data["bruised_points"][0].size == 4
    case["history"] = {"t_ms": np.array([0.0, 1.0]), "alpha_mm": np.zeros(2), "force_N": np.zeros(2),
                       "q_MPa": np.zeros(2)}
    case["summary"]["time_first_contact_s"] = 0.0
    text = report.numbers_text(case, data)
    assert "threshold ε̄p > 0 %" in text
    assert "plastic work 153 mJ, largest ε̄p 5 %" in text
    assert "residual flattening of the pole 1.15 mm" in text
