"""bc_train.py's image augmentation (issue 27): what it varies, by how much, and what it keeps."""
import importlib.util

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
        net = bc_train.UNetLstm(8, normalize_brightness=normalized)
        net.load_state_dict(shipped)
        net.eval()
        path = tmp_path / ("model_%d.pt" % normalized)
        torch.jit.script(net).save(str(path))  # what the C++ side loads
        scripted = torch.jit.load(str(path))
        with torch.no_grad():
            a, b = scripted.encode(x), scripted.encode(dim)
            change = float((a - b).norm() / a.norm())
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
    signed = [(hue_of(bc_train.augment(x, g)[0, :3].mean(dim=(1, 2))) + 180.0) % 360.0 - 180.0
              for _ in range(200)]
    assert min(signed) < 0.8 * low and max(signed) > 0.8 * high
    assert min(signed) > low - 15.0 and max(signed) < high + 15.0
