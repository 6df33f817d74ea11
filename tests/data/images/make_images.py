#!/usr/bin/python3
"""Writes the small images tests/cli/compare_test.sh compares; run once, the outputs are committed.

Debian's python3 with python3-numpy and python3-openimageio:
    /usr/bin/python3 tests/data/images/make_images.py

mask.scene (beside this script) shows its light quad in columns 0-7 of a 16x16 image, so those
are the "emitter" pixels; here they hold a bright value, and the other columns a gradient.
"""

import os

import numpy as np
import OpenImageIO as oiio

SIZE = 16
EMITTER_COLUMNS = slice(0, 8)
HERE = os.path.dirname(os.path.abspath(__file__))


def write_exr(name, rgb):
    spec = oiio.ImageSpec(rgb.shape[1], rgb.shape[0], 3, oiio.FLOAT)
    spec.attribute("compression", "zip")
    out = oiio.ImageOutput.create(os.path.join(HERE, name))
    if not out.open(os.path.join(HERE, name), spec):
        raise RuntimeError(oiio.geterror())
    out.write_image(rgb.astype(np.float32))
    out.close()


def main():
    ys, xs = np.mgrid[0:SIZE, 0:SIZE]
    gradient = 0.1 + 0.8 * (xs + SIZE * ys) / (SIZE * SIZE - 1)
    reference = np.stack([gradient, 0.5 * gradient, 1.0 - gradient], axis=-1)
    reference[:, EMITTER_COLUMNS, :] = 100.0
    write_exr("reference.exr", reference)

    # Off by 1% everywhere: RMSE about 0.7 over all pixels (the emitters dominate), 0.005 without.
    write_exr("close.exr", reference * 1.01)

    # Equal to the reference except on the emitter pixels.
    emitters_differ = reference.copy()
    emitters_differ[:, EMITTER_COLUMNS, :] = 50.0
    write_exr("emitters_differ.exr", emitters_differ)

    write_exr("small.exr", reference[:8, :8, :])


if __name__ == "__main__":
    main()
