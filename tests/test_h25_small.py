"""Issue 25, the smaller traps: the claims' difference, explore --quiet's dashboard line."""

import numpy as np
import xarray as xr

from ballcvt.reports.claims import CLAIMS, _sign_changes


class _Runs:
    def __init__(self, shift):
        x = np.linspace(0.5, 2.0, 14)  # no grid point on a sign change
        self.ds = xr.Dataset(
            {"creep": (("ratio", "contact"), (x - 1.0)[:, None]),
             "spin": (("ratio", "contact"), (x - 1.0 - shift)[:, None])},
            coords={"ratio": x, "contact": ["idler_a"]})

    def at40(self, arch):
        return self.ds


def test_fig10_difference_is_the_number_not_opposite():
    row = next(c for c in CLAIMS if c.figure == "Fig. 10")
    far = row.evaluate(_Runs(0.131))
    assert far.difference == "0.131 in tau_ID" and far.verdict == "differs"
    near = row.evaluate(_Runs(0.05))
    assert near.difference == "0.050 in tau_ID" and near.verdict == "agrees"
    assert _sign_changes(_Runs(0.131))[0] is False


def test_explore_quiet_prints_no_dashboard(capsys, monkeypatch):
    import ballcvt.analysis.studies.run as run

    class Fake:
        dashboard_link = "http://127.0.0.1:8787/status"

    monkeypatch.setattr(run, "local_client", lambda workers: Fake())
    run._connect(run.Compute(progress=False))
    assert "dashboard" not in capsys.readouterr().err
    run._connect(run.Compute(progress=True))
    assert "Dask dashboard: http://127.0.0.1:8787/status" in capsys.readouterr().err
