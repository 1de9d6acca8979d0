"""radchain.render against the command line: the same request gives the pixels and header cards of
`radchain render … --out x.fits --fits-type float` (read here with a minimal FITS reader: FITS Standard 4.0,
2880-byte blocks of 80-character cards, BITPIX -32 big-endian IEEE floats, NAXIS1 columns of NAXIS2 rows, the
bottom row stored first), for a
detector frame and an Earth scene; refusals are InputError with the command's message; `import radchain` alone
does not load the imaging libraries."""
import subprocess
import sys

import numpy as np
import pytest

import radchain


def read_fits(path):
    data = open(path, "rb").read()
    cards, offset = {}, 0
    while True:
        block = data[offset:offset + 2880].decode("ascii")
        offset += 2880
        for i in range(0, 2880, 80):
            card = block[i:i + 80]
            key = card[:8].strip()
            if key == "END":
                width, height = int(cards["NAXIS1"]), int(cards["NAXIS2"])
                assert int(cards["BITPIX"]) == -32
                pixels = np.frombuffer(data, dtype=">f4", count=width * height, offset=offset)
                return np.flipud(pixels.reshape(height, width)).astype(np.float32), cards  # top row first
            if card[8:10] == "= ":
                cards[key] = card[10:].split(" /")[0].strip()


def cli_render(cli, tmp_path, sensor, *args):
    out = tmp_path / "frame.fits"
    subprocess.run([cli.path, "render", str(sensor), "--out", str(out), "--fits-type", "float", *args], check=True,
                   capture_output=True)
    return read_fits(out)


def test_frame_equals_the_command_line(cli, tmp_path, sbv):
    image = radchain.render(sbv, width=40, height=30, stars=25, seed=7, star_seed=3, targets=[(10.5, 12.5, 14.0), "limit"])
    pixels, cards = cli_render(cli, tmp_path, sbv, "--width", "40", "--height", "30", "--stars", "25", "--seed", "7",
                               "--star-seed", "3", "--target", "10.5,12.5,14", "--target", "limit")
    assert image.kind == "frame" and image.pixels.shape == (30, 40) and image.pixels.dtype == np.float32
    np.testing.assert_array_equal(image.pixels, pixels)
    assert float(cards["EXPTIME"]) == pytest.approx(image.header["EXPTIME"], rel=1e-15)
    assert "point-target frame 40×30" in image.summary[0] and "2 targets, 25 stars" in image.summary[0]
    assert image.pixels.max() > image.pixels.mean()  # the 14th-magnitude target stands out


def test_scene_equals_the_command_line(cli, tmp_path, source_dir):
    sensor = source_dir / "sensors" / "kolobrodov-1996-ccd151-computed.toml"
    image = radchain.render(sensor, seed=5, gsd="6.7 m")
    pixels, cards = cli_render(cli, tmp_path, sensor, "--seed", "5", "--gsd", "6.7 m")
    assert image.kind == "scene"
    np.testing.assert_array_equal(image.pixels, pixels)
    for key, value in image.header.items():
        if isinstance(value, float) and key in cards:
            assert float(cards[key]) == pytest.approx(value, rel=1e-12), key


def test_datasheet_imager_scene_in_electrons(cli, tmp_path, source_dir):
    # A real imager (emva1288 on a reflectance target, a giqe MTF budget): the same pixels as the command line, and
    # without noise or ADC a flat map is the chain's own signal electrons at the file's reflectance.
    sensor = source_dir / "sensors" / "sentinel-2a-msi-b4.toml"
    image = radchain.render(sensor, seed=2)
    pixels, cards = cli_render(cli, tmp_path, sensor, "--seed", "2")
    np.testing.assert_array_equal(image.pixels, pixels)
    assert image.header["RADIOM"] == "electrons" and image.header["MTFOPT"] == "budget"
    signal = radchain.load(sensor).run()["detector.signal_electrons"]
    assert image.header["EPERRHO"] * image.header["RHO"] == pytest.approx(signal, rel=1e-12)


def test_refusals_are_input_errors(sbv):
    with pytest.raises(radchain.InputError, match=r"radchain.render: --width = 0: out of range"):
        radchain.render(sbv, width=0)
    with pytest.raises(radchain.InputError, match=r"--target"):
        radchain.render(sbv, targets=["1,2"])
    with pytest.raises(radchain.InputError, match=r"apperture"):
        radchain.render(sbv, set={"optics.apperture": "20 cm"})


def test_import_does_not_load_the_imaging_libraries():
    code = ("import radchain, sys; maps = open('/proc/self/maps').read(); "
            "print('radchain._imaging' in sys.modules, 'libOpenImageIO' in maps)")
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True).stdout.split()
    assert out == ["False", "False"]
