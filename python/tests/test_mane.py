"""The Python module as a specification: what a script sees is what `mane sim` and `mane render` see."""

import re
import subprocess

import numpy as np
import pytest

import mane
from png_reading import read_png

STEPS = 30


def test_stepping_gives_the_state_hash_mane_sim_prints(hair_ball, mane_program):
    # Same file, same loading, same fixed steps: the hash is bit-for-bit the program's.
    world = mane.World(hair_ball, load_textures=False)
    world.step(STEPS)
    run = subprocess.run([mane_program, "sim", str(hair_ball), "--steps", str(STEPS)],
                         capture_output=True, text=True, check=True)
    printed = re.search(r"state-hash: ([0-9a-f]{16})", run.stdout).group(1)
    assert f"{world.state_hash:016x}" == printed


def test_the_hash_does_not_depend_on_threads_or_textures(hair_ball):
    one = mane.World(hair_ball, load_textures=False)
    one.step(STEPS, threads=1)
    two = mane.World(hair_ball)
    two.step(STEPS, threads=2)
    assert one.state_hash == two.state_hash
    assert one.time == pytest.approx(STEPS * one.step_seconds)


def test_positions_are_guide_particles_as_float32_rows(hair_ball):
    world = mane.World(hair_ball, load_textures=False)
    assert world.groom_count == 1 and world.groom_names == ["hair"]
    positions = world.positions(0)
    offsets = world.strand_offsets(0)
    assert positions.dtype == np.float32 and positions.shape == (1024, 3)
    assert offsets.shape == (65,) and offsets[0] == 0 and offsets[-1] == 1024
    assert world.previous_positions(0).shape == (1024, 3)
    # Each strand starts at its root on the ball (radius 0.1 m, a tessellated sphere: within 1 mm)
    # and every other particle lies outside it.
    radii = np.linalg.norm(positions, axis=1)
    is_root = np.zeros(1024, bool)
    is_root[offsets[:-1]] = True
    np.testing.assert_allclose(radii[is_root], 0.1, atol=1e-3)
    assert np.all(radii[~is_root] > 0.1)


def test_written_positions_read_back_and_change_the_hash(hair_ball):
    world = mane.World(hair_ball, load_textures=False)
    world.step(5)
    before = world.state_hash
    written = world.positions(0)
    written[1:] += np.float32(0.001)
    world.set_positions(0, written)
    assert world.state_hash != before
    np.testing.assert_array_equal(world.positions(0), written)
    # Without `previous` the particles are left at rest.
    np.testing.assert_array_equal(world.previous_positions(0), written)

    moving = written - np.float32(0.0005)
    world.set_positions(0, written, previous=moving)
    np.testing.assert_array_equal(world.previous_positions(0), moving)
    world.step(1)
    assert np.all(np.isfinite(world.positions(0)))


def test_bad_positions_are_refused_and_change_nothing(hair_ball):
    world = mane.World(hair_ball, load_textures=False)
    before = world.state_hash
    with pytest.raises(ValueError, match="1024 rows"):
        world.set_positions(0, np.zeros((10, 3), np.float32))
    bad = world.positions(0)
    bad[7, 1] = np.nan
    with pytest.raises(mane.Error, match="entry 7 is not finite"):
        world.set_positions(0, bad)
    with pytest.raises(IndexError):
        world.positions(1)
    assert world.state_hash == before


def test_roots_reach_their_targets_by_the_end_of_the_step(hair_ball):
    # The roots move on straight lines to the targets through the advance and end on them.
    world = mane.World(hair_ball, load_textures=False)
    roots = world.strand_offsets(0)[:-1]
    targets = world.positions(0)[roots] + np.array([0.0, 0.01, 0.0], np.float32)
    world.set_root_targets(0, targets, world.root_rest_normals(0))
    world.step(1)
    np.testing.assert_allclose(world.positions(0)[roots], targets, atol=1e-6)
    with pytest.raises(ValueError, match="64 rows"):
        world.set_root_targets(0, targets[:3], world.root_rest_normals(0)[:3])


def test_a_missing_scene_raises_with_the_file_name(tmp_path):
    missing = tmp_path / "no_such_scene.json"
    with pytest.raises(mane.Error, match="no_such_scene.json"):
        mane.World(missing)


def test_render_returns_an_rgba_image_of_the_requested_size(hair_ball):
    world = mane.World(hair_ball)
    renderer = mane.Renderer(64, 48, msaa=1)
    image = renderer.render(world)
    assert image.dtype == np.uint8 and image.shape == (48, 64, 4)
    # Not blank: the grey ball and its hair over the background leave many distinct colours.
    assert len(np.unique(image[..., :3].reshape(-1, 3), axis=0)) > 10
    # The hair moves as the world steps, and the next frame shows it.
    world.step(10)
    assert not np.array_equal(renderer.render(world), image)


def test_frames_are_the_ones_mane_render_writes(hair_ball, mane_program, tmp_path):
    # Same device, same frame loop, same frames: byte for byte, the first and one after an advance.
    fps = 30
    subprocess.run([mane_program, "render", str(hair_ball), "--size", "64x48", "--msaa", "1", "--frames", "2",
                    "--fps", str(fps), "--out", str(tmp_path)], capture_output=True, check=True)
    world = mane.World(hair_ball)
    renderer = mane.Renderer(64, 48, msaa=1)
    for frame in range(2):
        if frame > 0:
            world.advance(1.0 / fps)
        image = renderer.render(world, frame_seconds=1.0 / fps)
        written = read_png(tmp_path / f"hair_ball_{frame:04d}.png")
        np.testing.assert_array_equal(image[..., :written.shape[2]], written, err_msg=f"frame {frame}")
