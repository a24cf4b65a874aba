"""Analysis(spec="my.toml"): a model derived at run time, with the numbers of the compiled model
of the same spec."""

import os
import shutil

import pytest

import flaplag

SPEC_DIR = os.environ.get("FLAPLAG_SPEC_DIR", "")
PAPER = os.path.join(SPEC_DIR, "paper.toml")


@pytest.fixture(autouse=True)
def _spec_dir():
    if not SPEC_DIR:
        pytest.fail("FLAPLAG_SPEC_DIR is not set (run the tests through ctest)")


def test_shipped_spec_equals_the_compiled_model():
    compiled = flaplag.Analysis()
    run_time = flaplag.Analysis(spec=PAPER)
    assert run_time.model.name == "spec:paper"
    a, b = compiled.critical(), run_time.critical()
    assert a.mu_c is not None and a.mu_c == b.mu_c
    assert a.mode == b.mode


def test_any_mode_counts():
    kw = dict(modes="exact", flap_modes=2, lag_modes=1)
    compiled = flaplag.Analysis(**kw).point(0.3)
    run_time = flaplag.Analysis(spec=PAPER, **kw)
    assert run_time.model.name == "spec:paper-2x1"
    assert [e for e in run_time.point(0.3).exponents] == [e for e in compiled.exponents]


def test_user_spec_in_a_scratch_directory(tmp_path):
    shutil.copy(PAPER, tmp_path / "paper.toml")
    (tmp_path / "mine.toml").write_text('base = "paper"\n[terms]\nradial_flow = false\n')
    run_time = flaplag.Analysis(spec=tmp_path / "mine.toml")
    compiled = flaplag.Analysis(model="no-radial-flow")
    assert run_time.critical().mu_c == compiled.critical().mu_c


def test_bad_spec_is_a_one_line_value_error(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('[kept]\nflap = "two"\n')
    with pytest.raises(ValueError) as e:
        flaplag.Analysis(spec=str(bad))
    text = str(e.value)
    # (a long path is shortened in the message)
    assert text.startswith("spec = ")
    assert ': bad.toml: kept.flap = "two": must be an integer' in text
    assert "\n" not in text
    with pytest.raises(ValueError):
        flaplag.Analysis(spec=str(tmp_path / "missing.toml"))
    with pytest.raises(ValueError, match="not with spec"):
        flaplag.Analysis(spec=PAPER, model="paper")
