"""Result.quantity(): every result of every bundled sensor file as an astropy Quantity in its SI unit, and astropy's
own conversion of that Quantity to the report's display unit equals radchain's display value (udunits2 does the
conversion in radchain: two unit libraries agreeing is the check). Display units astropy cannot read ("DN/e-":
astropy's DN is not an inverse electron) are left out and counted."""
import math

import pytest

import radchain

u = pytest.importorskip("astropy.units")  # python3-astropy (scripts/setup-debian.sh)

ASTROPY_NAMES = {"e-": "electron"}  # radchain's display name of the electron (udunits: "e-" via its own table)


def test_every_result_converts_like_the_report(source_dir):
    checked = skipped = 0
    for path in sorted((source_dir / "sensors").glob("*.toml")):
        r = radchain.load(path).run()
        for name in r:
            record = r.record(name)
            q = r.quantity(name)
            assert isinstance(q, u.Quantity), name
            assert q.value == record.value_si or (math.isnan(q.value) and math.isnan(record.value_si)), name
            if not math.isfinite(record.value) or record.unit in ("", "1"):
                continue
            try:
                display = u.Unit(" ".join(ASTROPY_NAMES.get(t, t) for t in record.unit.replace("/", " / ").split()))
                converted = q.to(display).value
            except (ValueError, u.UnitsError):
                skipped += 1
                continue
            assert converted == pytest.approx(record.value, rel=1e-12, abs=1e-300), f"{path.name}: {name} [{record.unit}]"
            checked += 1
    # measured: 1163 checked, 22 left out (every one a gain in DN/e-, a unit astropy does not name): under 2.5 %
    assert checked > 1100 and skipped < 0.025 * checked, (checked, skipped)


def test_quantity_without_a_unit_is_dimensionless(sbv):
    r = radchain.load(sbv).run()
    assert r.quantity("detector.snr").unit == u.dimensionless_unscaled
    assert r.quantity("optics.aperture").to(u.cm).value == pytest.approx(15.0, rel=1e-15)
    assert set(r.quantities()) == set(r.names)
