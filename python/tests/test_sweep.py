"""visco2d.batch's sweep arithmetic: values, axes, their product, placeholders, case names."""
import pytest

from visco2d import batch


def test_range_includes_both_ends():
    assert batch.parse_values("h", "0.1:0.3:3", "--param") == ["0.1", "0.2", "0.3"]
    assert batch.parse_values("h", "0.5:0.9:1", "--param") == ["0.5"]


def test_range_refused_before_it_is_made():
    with pytest.raises(batch.UsageError, match="more than the 10 cases"):
        batch.parse_values("h", "0:1:100000000", "--param", limit=10)


def test_bad_ranges_are_usage_errors():
    for text in ("0:1", "a:1:3", "0:1:0", "0:inf:3", "1,,2"):
        with pytest.raises(batch.UsageError):
            batch.parse_values("h", text, "--param")


def test_product_and_zip():
    heights = batch.param_axis("height=0.1,0.2")
    radii = batch.param_axis("radius=0.03,0.04")
    product = batch.combine([heights, radii], zipped=False)
    assert product == [{"height": "0.1", "radius": "0.03"}, {"height": "0.1", "radius": "0.04"},
                       {"height": "0.2", "radius": "0.03"}, {"height": "0.2", "radius": "0.04"}]
    assert batch.combine([heights, radii], zipped=True) == [{"height": "0.1", "radius": "0.03"},
                                                             {"height": "0.2", "radius": "0.04"}]
    with pytest.raises(batch.UsageError, match="different lengths"):
        batch.combine([heights, batch.param_axis("nu=0.3")], zipped=True)


def test_placeholders_located_and_stray_dollar():
    found = batch.placeholders("t.inp", "TITLE x\nDROP HEIGHT=${height} $$\nMESH R=${radius}\n")
    assert found == {"height": "t.inp:2:13", "radius": "t.inp:3:8"}
    with pytest.raises(batch.UsageError, match="t.inp:1:7"):
        batch.placeholders("t.inp", "TITLE $ 5\n")


def test_case_names_safe_and_bounded():
    assert batch.case_name("peach", {"height": "0.1", "pad": "a b"}, 0) == "peach__height=0.1__pad=a_b"
    long = {"x%d" % k: "1" * 20 for k in range(10)}
    assert batch.case_name("peach", long, 6) == "peach__case=7"
    assert batch.case_name("x", {"case": ".hidden"}, 0) == "_hidden"
