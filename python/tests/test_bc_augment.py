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
