"""bc_train.py's image augmentation (issue 27): what it varies, by how much, and what it keeps."""
import importlib.util
import math

import pytest

torch = pytest.importorskip("torch")
pytest.importorskip("PIL")


@pytest.fixture
def bc_train(source_dir):
    spec = importlib.util.spec_from_file_location("bc_train", source_dir / "python" / "bc_train.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def window(frames=6):
    """A scene-like window: a smooth RGB gradient at mid brightness and a disparity ramp."""
    g = torch.Generator().manual_seed(3)
    y = torch.linspace(0.2, 0.7, 60)[:, None].expand(60, 80)
    rgb = torch.stack([y, 0.8 * y, 0.6 * y]) + 0.02 * torch.rand(3, 60, 80, generator=g)
    disparity = torch.linspace(0.1, 1.0, 80)[None, None].expand(1, 60, 80)
    return torch.cat([rgb, disparity]).expand(frames, 4, 60, 80).clone()


def feature_change(bc_train, weights, path, a, b, **options):
    """How much the features of frames `a` and `b` differ (relative), through the network of
    `options` with `weights`, exported to TorchScript at `path` and loaded back as the C++ side
    loads it."""
    net = bc_train.UNetLstm(8, **options)
    net.load_state_dict(weights)
    net.eval()
    torch.jit.script(net).save(str(path))
    scripted = torch.jit.load(str(path))
    with torch.no_grad():
        fa, fb = scripted.encode(a), scripted.encode(b)
    return float((fa - fb).norm() / fa.norm())


def test_augment_stays_in_range_and_keeps_the_input(bc_train):
    x = window()
    before = x.clone()
    g = torch.Generator().manual_seed(1)
    for _ in range(50):
        a = bc_train.augment(x, g)
        assert a.shape == x.shape
        assert torch.isfinite(a).all()
        assert a[:, :3].min() >= 0.0 and a[:, :3].max() <= 1.0
        assert a[:, 3].min() >= 0.0
    assert torch.equal(x, before)  # a new tensor; the cached frames stay as recorded


def test_brightness_spans_its_training_range_and_not_the_dim_shift(bc_train):
    x = window()
    g = torch.Generator().manual_seed(2)
    ratios = torch.tensor([float(bc_train.augment(x, g)[:, :3].mean() / x[:, :3].mean())
                           for _ in range(400)])
    low, high = bc_train.AUGMENT_BRIGHTNESS
    # the mean brightness follows the gain (contrast keeps the mean; noise and clipping little)
    assert ratios.min() < low * 1.25 and ratios.max() > high * 0.8
    assert ratios.min() > 0.25 / 0.45 * low  # never as dark as bc_evaluate's dim shift (0.25)


def test_the_same_draw_for_every_frame_of_a_window(bc_train):
    x = window()
    a = bc_train.augment(x, torch.Generator().manual_seed(5))
    means = a[:, :3].mean(dim=(1, 2, 3))
    assert float(means.max() - means.min()) < 0.01  # frames differ only by their pixel noise
    d = a[:, 3]
    lost = (d == 0.0).float().mean()
    assert float(lost) <= bc_train.AUGMENT_DISPARITY_DROPOUT + 0.01


def test_the_same_generator_seed_gives_the_same_window(bc_train):
    x = window()
    a = bc_train.augment(x, torch.Generator().manual_seed(9))
    b = bc_train.augment(x, torch.Generator().manual_seed(9))
    c = bc_train.augment(x, torch.Generator().manual_seed(10))
    assert torch.equal(a, b)
    assert not torch.equal(a, c)


def test_normalized_brightness_makes_the_features_independent_of_the_light(bc_train, tmp_path,
                                                                          source_dir):
    # the shipped network's weights (trained without the normalisation): features that see light
    shipped = torch.jit.load(str(source_dir / "models" / "bc_final.pt")).state_dict()
    x = window(3)
    dim = x.clone()
    dim[:, :3] *= 0.25  # bc_evaluate's dim shift, outside the training ranges
    for normalized in (False, True):
        change = feature_change(bc_train, shipped, tmp_path / ("model_%d.pt" % normalized), x, dim,
                                normalize_brightness=normalized)
        if normalized:
            assert change < 0.05
            # the frame's mean RGB is scaled to the reference, the disparity left as it is
            scale = bc_train.REFERENCE_BRIGHTNESS / (
                float(dim[:, :3].mean(dim=(1, 2, 3))[0]) + bc_train.BRIGHTNESS_FLOOR)
            assert 0.9 * bc_train.REFERENCE_BRIGHTNESS < float(dim[0, :3].mean()) * scale \
                < 1.1 * bc_train.REFERENCE_BRIGHTNESS
        else:
            assert change > 0.2


def test_hue_rotation_turns_colours_and_keeps_the_blue_shift_out_of_training(bc_train):
    import colorsys

    def hue_of(rgb):
        return colorsys.rgb_to_hsv(*[float(v) for v in rgb.clamp(0.0, 1.0)])[0] * 360.0

    def apart(a, b):
        return abs((a - b + 180.0) % 360.0 - 180.0)

    grey = torch.tensor([0.4, 0.4, 0.4])
    assert torch.allclose(bc_train.hue_rotation(37.0) @ grey, grey, atol=1e-6)
    red = torch.tensor([0.8, 0.16, 0.16])
    assert apart(hue_of(bc_train.hue_rotation(30.0) @ red), 30.0) < 3.0
    assert apart(hue_of(bc_train.hue_rotation(-60.0) @ red), 300.0) < 3.0
    # the recorder's target hues (-25 to 130 deg, saturation 0.6-1, value 0.55-1) through the
    # augmentation's whole hue range stay at least 45 deg from the blue_target shift (225 deg)
    low, high = bc_train.AUGMENT_HUE
    closest = 180.0
    for hue in range(-25, 131, 5):
        for saturation, value in ((0.6, 0.55), (1.0, 1.0), (0.8, 0.7)):
            rgb = torch.tensor(colorsys.hsv_to_rgb((hue % 360) / 360.0, saturation, value))
            for turn in torch.linspace(low, high, 22):
                closest = min(closest, apart(hue_of(bc_train.hue_rotation(float(turn)) @ rgb),
                                             225.0))
    assert closest > 45.0
    # and the augmentation draws that range: a red window's hue moves both ways by up to it
    x = torch.cat([red[None, :, None, None].expand(4, 3, 60, 80),
                   torch.full((4, 1, 60, 80), 0.5)], dim=1)
    g = torch.Generator().manual_seed(4)
    means = [bc_train.augment(x, g)[0, :3].mean(dim=(1, 2)) for _ in range(200)]
    # (the windows the saturation draw turned grey have no hue to measure)
    signed = [(hue_of(m) + 180.0) % 360.0 - 180.0 for m in means if float(m.max() - m.min()) > 0.05]
    assert min(signed) < 0.8 * low and max(signed) > 0.8 * high
    assert min(signed) > low - 15.0 and max(signed) < high + 15.0


def test_zoom_scales_the_image_and_keeps_the_disparity_values(bc_train):
    # a bright square 20 px wide in the middle, its disparity 0.8 on a background of 0.2
    x = torch.zeros(2, 4, 60, 80)
    x[:, :3, 20:40, 30:50] = 1.0
    x[:, 3] = 0.2
    x[:, 3, 20:40, 30:50] = 0.8
    for scale in (0.8, 1.25):
        rgb, disparity = bc_train.zoom(x[:, :3], x[:, 3:], scale)
        width = float((rgb[0, 0, 30] > 0.5).sum())
        assert abs(width - 20.0 * scale) <= 1.0
        # the disparity is sampled, not rescaled: the object is as far as before
        assert all(min(abs(v - 0.2), abs(v - 0.8)) < 1e-6
                   for v in torch.unique(disparity).tolist())
        assert abs(float((disparity[0, 0, 30] > 0.5).sum()) - 20.0 * scale) <= 1.0
    rgb, disparity = bc_train.zoom(x[:, :3], x[:, 3:], 1.0)
    assert torch.equal(rgb, x[:, :3]) and torch.equal(disparity, x[:, 3:])
    # augment() draws the zoom over its whole range, one per window
    low, high = bc_train.AUGMENT_ZOOM
    g = torch.Generator().manual_seed(6)
    widths = []
    for _ in range(300):
        d = bc_train.augment(x, g)[:, 3] > 0.5
        # the frames share the zoom (they differ by the disparity's noise and lost pixels)
        assert float((d[0] ^ d[1]).float().sum()) < 0.15 * float(d[0].float().sum())
        widths.append(float(d.float().sum(dim=(1, 2)).max()) ** 0.5)  # the square's side
    assert min(widths) <= 20.0 * low + 2.0 and max(widths) >= 20.0 * high - 2.0
    assert min(widths) >= 20.0 * low - 3.0 and max(widths) <= 20.0 * high + 3.0


def test_saturation_weakens_the_colour_and_sometimes_removes_it(bc_train):
    red = torch.tensor([0.8, 0.16, 0.16])
    x = torch.cat([red[None, :, None, None].expand(3, 3, 60, 80),
                   torch.full((3, 1, 60, 80), 0.5)], dim=1)
    g = torch.Generator().manual_seed(8)
    chroma = []
    for _ in range(400):
        mean = bc_train.augment(x, g)[0, :3].mean(dim=(1, 2))
        chroma.append(float(mean.max() - mean.min()) / float(red.max() - red.min()))
    chroma = torch.tensor(chroma)
    grey = float((chroma < 0.05).float().mean())  # pixel noise only: the window turned grey
    assert abs(grey - bc_train.AUGMENT_GREY) < 0.06
    coloured = chroma[chroma >= 0.05]
    low, high = bc_train.AUGMENT_SATURATION
    # the colour's strength spans the saturation range (times the brightness and contrast draws)
    assert float(coloured.min()) < 1.5 * low and float(coloured.max()) > 0.9 * high


def test_hue_blind_features_do_not_depend_on_the_targets_hue(bc_train, tmp_path, source_dir):
    shipped = torch.jit.load(str(source_dir / "models" / "bc_final.pt")).state_dict()
    x = window(3)
    target = torch.tensor(bc_train.REFERENCE_HUE_RGB)
    x[:, :3, 20:45, 35:45] = target[None, :, None, None]  # the default red-orange target
    blue = x.clone()  # the same target turned to the blue_target shift's hue (225 deg)
    patch = blue[:, :3, 20:45, 35:45]
    blue[:, :3, 20:45, 35:45] = torch.einsum("ij,fjhw->fihw", bc_train.hue_rotation(-140.0),
                                             patch)
    import colorsys
    hue = colorsys.rgb_to_hsv(*[float(v) for v in blue[0, :3, 30, 40]])[0] * 360.0
    assert 215.0 < hue < 235.0
    for blind in (False, True):
        change = feature_change(bc_train, shipped, tmp_path / ("model_%d.pt" % blind), x, blue,
                                normalize_brightness=True, hue_blind=blind)
        if blind:
            assert change < 1e-5
        else:
            assert change > 0.05
    # the reference hue is left as it is, a grey pixel stays grey
    net = bc_train.UNetLstm(8, hue_blind=True)
    reference = torch.tensor(bc_train.hue_direction(bc_train.REFERENCE_HUE_RGB))
    grey = target.mean()
    assert torch.allclose(grey + (target - grey).norm() * reference, target, atol=1e-6)
    assert torch.allclose(torch.tensor(net.reference_hue), reference)


def test_the_camera_pitch_moves_the_image_up_and_down_by_up_to_its_range(bc_train):
    # a band of near disparity across the middle rows: the zoom keeps its centre, the pitch moves it
    x = torch.full((2, 4, 60, 80), 0.3)
    x[:, 3] = 0.2
    x[:, 3, 28:32] = 0.8
    g = torch.Generator().manual_seed(12)
    offsets = []
    for _ in range(300):
        d = bc_train.augment(x, g)[0, 3, :, 40] > 0.5
        rows = torch.nonzero(d).flatten().float()
        offsets.append(float(rows.mean()) - 29.5)
    offsets = torch.tensor(offsets)
    pitch = bc_train.AUGMENT_PITCH
    assert float(offsets.abs().max()) <= pitch + 1.0
    assert float(offsets.min()) < -pitch + 2.0 and float(offsets.max()) > pitch - 2.0
    # 60 rows span the chest camera's 45 deg: the pitch stays a jitter of some degrees
    assert 5.0 <= pitch * 45.0 / 60.0 <= 12.0


def test_uneven_light_ramps_and_casts_shadows_within_its_ranges(bc_train):
    g = torch.Generator().manual_seed(14)
    ramps, shadows = [], 0
    for _ in range(300):
        f = bc_train.uneven_light((4, 3, 60, 80), g)[0, 0]
        assert f.shape == (60, 80) and torch.isfinite(f).all()
        low, high = bc_train.AUGMENT_SHADOW
        assert float(f.min()) >= low * math.exp(-bc_train.AUGMENT_SHADING) - 1e-6
        assert float(f.max()) <= math.exp(bc_train.AUGMENT_SHADING) + 1e-6
        ramps.append(float(f.max() / f.min()))
        # a shadow: a jump between neighbouring pixels far larger than the smooth ramp's
        jumps = torch.cat([(f[1:] / f[:-1]).flatten(), (f[:, 1:] / f[:, :-1]).flatten()])
        if float((jumps - 1.0).abs().max()) > 0.9 * (1.0 / high - 1.0):
            shadows += 1
    assert max(ramps) > math.exp(0.8 * bc_train.AUGMENT_SHADING)
    assert abs(shadows / 300.0 - bc_train.AUGMENT_SHADOW_P) < 0.1
