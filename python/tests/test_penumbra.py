"""The Python module against the command line: the same images, the same messages, and a flat
memory over many frames. Run by CTest (python.pytest) with PYTHONPATH at the built module."""

import os
import re
import subprocess

import numpy as np
import OpenImageIO as oiio
import pytest

import penumbra

BINARY = os.environ["PENUMBRA_BINARY"]
SOURCE = os.environ["PENUMBRA_SOURCE_DIR"]
SHADOW_BOX = os.path.join(SOURCE, "scenes", "shadow_box.scene")
# Small and cheap, the same for the module and the command line.
SETTINGS = {"vpls": 16, "voxel_resolution": 32}
CLI_SETTINGS = ["--vpls", "16", "--voxel-resolution", "32"]


def read_exr(path):
    image = oiio.ImageInput.open(path)
    pixels = image.read_image(format="float")
    image.close()
    return pixels


def cli_render(tmp_path, *arguments):
    output = str(tmp_path / "cli.exr")
    subprocess.run([BINARY, "render", SHADOW_BOX, "--size", "32x32", *CLI_SETTINGS, *arguments,
                    "-o", output], check=True, capture_output=True)
    return read_exr(output)


@pytest.mark.parametrize("visibility", ["voxels", "bvh"])
@pytest.mark.parametrize("mode", ["hierarchical", "naive"])
def test_render_equals_the_cli_exr(tmp_path, mode, visibility):
    scene = penumbra.load_scene(SHADOW_BOX)
    image = penumbra.render(scene, size=(32, 32), mode=mode, visibility=visibility, **SETTINGS)
    assert image.dtype == np.float32 and image.shape == (32, 32, 3)
    # Identical: the same code renders the same frame, and EXR stores the same floats.
    expected = cli_render(tmp_path, "--mode", mode, "--visibility", visibility)
    assert np.array_equal(image, expected[:, :, 0:3])
    assert image.any()


def test_light_proximity_threshold_equals_the_cli_option(tmp_path):
    scene = penumbra.load_scene(SHADOW_BOX)
    # Three levels (32, 16 and 8 texels), so that there are coarse texels to refine.
    image = penumbra.render(scene, size=(32, 32), coarsest=8, light_proximity_threshold=0.02,
                            **SETTINGS)
    expected = cli_render(tmp_path, "--coarsest", "8", "--light-proximity-threshold", "0.02")
    assert np.array_equal(image, expected[:, :, 0:3])
    # It took effect: the default threshold refines fewer texels near the light.
    assert not np.array_equal(image, penumbra.render(scene, size=(32, 32), coarsest=8, **SETTINGS))


def test_voxel_shape_equals_the_cli_option(tmp_path):
    scene = penumbra.load_scene(SHADOW_BOX)
    image = penumbra.render(scene, size=(32, 32), voxel_shape="equal", **SETTINGS)
    expected = cli_render(tmp_path, "--voxel-shape", "equal")
    assert np.array_equal(image, expected[:, :, 0:3])
    # It took effect: the default cubic grid's voxels shadow the box differently.
    assert not np.array_equal(image, penumbra.render(scene, size=(32, 32), **SETTINGS))


@pytest.mark.parametrize("mode", ["reference", "reference-vpl"])
def test_reference_equals_the_cli_exr(tmp_path, mode):
    scene = penumbra.load_scene(SHADOW_BOX)
    image = penumbra.render(scene, size=(32, 32), mode=mode, spp=4, seed=7, vpls=16)
    expected = cli_render(tmp_path, "--mode", mode, "--spp", "4", "--seed", "7")
    assert np.array_equal(image, expected[:, :, 0:3])
    assert image.any()


def test_aovs_equal_the_debug_views(tmp_path):
    scene = penumbra.load_scene(SHADOW_BOX)
    result = penumbra.render(scene, size=(32, 32), aovs=["albedo", "depth"], statistics=True,
                             **SETTINGS)
    assert set(result) == {"radiance", "albedo", "depth", "statistics"}
    for view in ["albedo", "depth"]:
        expected = cli_render(tmp_path, "--debug-view", view)[:, :, 0:3]
        assert np.array_equal(result[view], expected), view
    statistics = result["statistics"]
    assert statistics["mode"] == "hierarchical" and statistics["vpls_per_light"] == 16
    assert statistics["samples_gathered"] > 0


def cli_error(*arguments):
    run = subprocess.run([BINARY, "render", *arguments], capture_output=True, text=True)
    assert run.returncode != 0
    return run.stderr.strip().splitlines()[-1]


def test_bad_setting_raises_the_cli_message(tmp_path):
    scene = penumbra.load_scene(SHADOW_BOX)
    message = cli_error(SHADOW_BOX, "--vpls", "3", "-o", str(tmp_path / "x.exr"))
    expected = message.removeprefix("penumbra: error: ")
    assert expected != message
    with pytest.raises(ValueError, match=re.escape(expected)):
        penumbra.render(scene, size=(32, 32), vpls=3)


def test_bad_scene_raises_the_cli_message(tmp_path):
    path = tmp_path / "bad.scene"
    path.write_text("material m\n  dif 2 0 0\nend\n")
    expected = cli_error(str(path), "-o", str(tmp_path / "x.exr"))
    with pytest.raises(penumbra.SceneError) as error:
        penumbra.load_scene(str(path))
    assert str(error.value) == expected


def test_unknown_keyword_is_an_error():
    scene = penumbra.load_scene(SHADOW_BOX)
    with pytest.raises(ValueError, match="unknown keyword argument 'vlps'"):
        penumbra.render(scene, size=(32, 32), vlps=16)


def quad(y, size):
    """Positions and triangles of a square at height y facing +y."""
    half = size / 2
    positions = np.array([[-half, y, -half], [-half, y, half], [half, y, half], [half, y, -half]],
                         dtype=np.float32)
    return positions, np.array([[0, 1, 2], [0, 2, 3]], dtype=np.uint32)


def built_scene(texture=None):
    positions, triangles = quad(0.0, 4.0)
    glow = {"name": "glow", "emission": (4, 4, 4)}
    if texture is not None:
        glow["texture"] = texture
    return penumbra.build_scene(
        materials=[{"name": "floor", "diffuse": (0.8, 0.8, 0.8)}, glow],
        lights=[{"name": "panel", "material": "glow", "at": (0, 0, 0),
                 "corners": np.array([[-0.5, 2, -0.5], [0.5, 2, -0.5], [0.5, 2, 0.5],
                                      [-0.5, 2, 0.5]])}],
        camera={"position": (0, 2, 3), "target": (0, 0, 0), "size": (32, 32)},
        objects=[{"positions": positions, "triangles": triangles, "material": "floor"}])


def test_scene_from_numpy_matches_its_file(tmp_path):
    texture = np.zeros((2, 2, 3), dtype=np.float32)
    texture[:, 0] = (1, 0.2, 0.2)
    texture[:, 1] = (0.2, 0.2, 1)
    positions, _ = quad(0.0, 4.0)
    obj = tmp_path / "floor.obj"
    obj.write_text("".join(f"v {x} {y} {z}\n" for x, y, z in positions) + "f 1 2 3\nf 1 3 4\n")
    png = str(tmp_path / "texture.exr")
    output = oiio.ImageOutput.create(png)
    output.open(png, oiio.ImageSpec(2, 2, 3, "float"))
    output.write_image(texture)
    output.close()
    (tmp_path / "built.scene").write_text(
        "material floor\n  dif 0.8 0.8 0.8\nend\n"
        f"material glow\n  emit 4 4 4\n  tex {png}\nend\n"
        "area_light panel\n  pos1 -0.5 2 -0.5\n  pos2 0.5 2 -0.5\n  pos3 0.5 2 0.5\n"
        "  pos4 -0.5 2 0.5\n  at 0 0 0\n  mat glow\nend\n"
        "camera camera\n  pos 0 2 3\n  at 0 0 0\n  screen_size 32 32\nend\n"
        f"object {obj}\n  mat floor\nend\n")
    from_file = penumbra.render(penumbra.load_scene(str(tmp_path / "built.scene")), **SETTINGS)
    from_arrays = penumbra.render(built_scene(texture), **SETTINGS)
    assert np.array_equal(from_arrays, from_file)
    assert from_file.any()


def test_bad_array_raises_the_builders_message():
    with pytest.raises(penumbra.SceneError,
                       match=re.escape("'dif' values must be in [0, 1], found '2'")):
        penumbra.build_scene(materials=[{"name": "m", "diffuse": (2, 0, 0)}])


def test_compare():
    a = np.zeros((4, 4, 3), dtype=np.float32)
    b = np.ones((4, 4, 3), dtype=np.float32)
    metrics = penumbra.compare(a, b)
    assert metrics["rmse"] == 1.0 and metrics["max"] == 1.0 and metrics["mae"] == 1.0
    assert penumbra.compare(b, b)["rmse"] == 0.0


def test_reuse_visibility_keyword():
    renderer = penumbra.Renderer(penumbra.load_scene(SHADOW_BOX), size=(32, 32))
    first = renderer.render(statistics=True, **SETTINGS)
    again = renderer.render(statistics=True, **SETTINGS)
    assert not first["statistics"]["visibility_reused"]
    assert again["statistics"]["visibility_reused"]
    # No light of the box has a video, so the reused frame keeps every light's gathered sums.
    assert first["statistics"]["gather_vpls_kept"] == 0
    assert again["statistics"]["gather_vpls_kept"] == again["statistics"]["vpls_per_light"]
    # Reuse is exact: the kept masks are those the frame would trace.
    assert np.array_equal(again["radiance"], first["radiance"])
    traced = renderer.render(statistics=True, reuse_visibility=False, **SETTINGS)
    assert not traced["statistics"]["visibility_reused"]
    assert traced["statistics"]["shadow_rays"] > 0


def resident_kib():
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    raise AssertionError("no VmRSS")


def test_many_frames_keep_memory_flat():
    renderer = penumbra.Renderer(built_scene(), size=(32, 32))
    for frame in range(10):
        renderer.render(frame=frame, aovs=["albedo"], statistics=True, **SETTINGS)
    before = resident_kib()
    for frame in range(10, 110):
        renderer.render(frame=frame, aovs=["albedo"], statistics=True, **SETTINGS)
    growth = resident_kib() - before
    # One frame's G-buffer, pyramid and results at 32x32 are about 200 KiB; leaking them for
    # each of 100 frames would add 20 MiB. 2 MiB leaves room for the allocator's own slack.
    assert growth < 2048, f"resident memory grew by {growth} KiB over 100 frames"


def test_renders_release_the_gil():
    # A reference render on another thread (about half a second here); while it runs, this
    # thread must run Python. Holding the GIL through the render would leave it at most the few
    # microseconds between `started` and the call, a few hundred iterations, not 100000.
    import threading
    scene = penumbra.load_scene(SHADOW_BOX)
    started = threading.Event()
    done = threading.Event()

    def render():
        started.set()
        penumbra.render(scene, size=(64, 64), mode="reference", spp=256, vpls=16)
        done.set()

    thread = threading.Thread(target=render)
    thread.start()
    started.wait()
    iterations = 0
    while not done.is_set():
        iterations += 1
    thread.join()
    assert iterations > 100000, f"only {iterations} iterations while rendering: the GIL was held"
