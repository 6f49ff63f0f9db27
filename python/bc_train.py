#!/usr/bin/python3
"""Behavioural cloning (thesis §7.1, §11.1.1, figure 11.2): trains the U-Net-LSTM on recorded
demonstrations (examples/record_demonstrations, bc_evaluate --dagger: index.txt, rgb/,
disparity/) and exports it as TorchScript for the C++ controller.

    /usr/bin/python3 python/bc_train.py DATA [DATA ...] OUT [--epochs 30] [--batch 32]
                                          [--lr 1e-3] [--sequence 5] [--chunk 16] [--width 8]
                                          [--seed 0] [--max-steps N] [--threads 2]
                                          [--init OUT/best.pth] [--augment]
                                          [--normalize-brightness] [--hue-blind]

Pre-processing (the C++ side, walkgen/torch/velocity_network.hpp, does the same): the left RGB
image and the WLS disparity (240 x 320) are averaged over 4 x 4 blocks to 60 x 80; RGB is scaled
to [0, 1], disparity [px] divided by 32 (D of the thesis); the four channels are stacked to
RGBD. The processed frames of each folder are cached in DATA/bc_frames_60x80.npy. With
--normalize-brightness the network itself (its `encode`, so the exported model and the C++ side
alike) first scales each frame's RGB so that its mean is REFERENCE_BRIGHTNESS: a frame lit twice
as brightly or four times as dimly gives the same features (up to quantisation, noise and
clipping), while colours keep their ratios. With --hue-blind it then turns every pixel's colour
to one hue (REFERENCE_HUE_RGB's, the default target's red-orange), keeping its grey level and how
strongly coloured it is: the network sees how colourful a thing is, never which colour, so a
target of any hue looks like the targets it was trained on (and it cannot tell two objects apart
by hue alone: the distractor of the navigation rooms differs from the target by 15 degrees of hue
and stays told apart by its shape, brightness and place).

Samples are the thesis's sequences: the command after a frame is regressed from that frame and
the `sequence` - 1 before it (5 frames, 2 s at the NMPC's 0.4 s ticks), each frame encoded by
the U-Net and a fully connected layer, the sequence run through the LSTM from a zero state; an
episode's first frame stands in for the frames before it (the robot stands still then). The
C++ side keeps the last `sequence` encoded frames and does the same, so training and the loop
see the same inputs. For speed, a batch holds windows of `chunk` consecutive frames, each frame
encoded once, with one sequence ending at each of its last chunk - sequence + 1 frames. Targets:
(v_x, omega_z) divided by the generator's limits (Heicub's 0.034 m/s and 0.075 rad/s), so the
network's tanh output times the limits is the command.

Split: about 90 % of the episodes for training, 10 % (at least one) for validation, chosen by
a hash of the episode's name, so that the validation frames come from rooms the network has not
seen (the thesis split frames at random) and the split does not change when data is added.
The weights with the best validation loss are kept. Writes to OUT: command.txt (this command
line), model.pt (TorchScript, with
`encode(frame)`, `head(features)` and the attributes `sequence` and `hidden`), training_log.csv
(epoch, train and validation MSE, seconds), training.png (the loss curves, figure 11.3), and
histograms.png and histograms.csv: ground truth vs prediction on the validation split with the
KL divergence (eq. 11.1) and the entropy (eq. 9.1) of each velocity.
"""
import argparse
import math
import os
import random
import shlex
import sys
import time
import zlib

import numpy as np
import torch
import torch.nn as nn
import torch.nn.functional as F
from PIL import Image

MAX_COMMAND = (0.034, 0.075)  # v_x [m/s], omega_z [rad/s]: heicub_settings().max_command
DISPARITY_SCALE = 32.0
HEIGHT, WIDTH = 60, 80


def block_mean(image, factor=4):
    """Averages factor x factor blocks (the C++ side does the same, cv::INTER_AREA-free)."""
    h, w = image.shape[0] // factor * factor, image.shape[1] // factor * factor
    image = image[:h, :w]
    shape = (h // factor, factor, w // factor, factor) + image.shape[2:]
    return image.reshape(shape).mean(axis=(1, 3))


def load_frame(folder, rgb_path, disparity_path):
    rgb = np.asarray(Image.open(os.path.join(folder, rgb_path)).convert("RGB"), dtype=np.float32)
    disparity = np.asarray(Image.open(os.path.join(folder, disparity_path)), dtype=np.float32)
    rgb = block_mean(rgb) / 255.0
    disparity = block_mean(disparity / 16.0) / DISPARITY_SCALE
    frame = np.concatenate([rgb.transpose(2, 0, 1), disparity[None]], axis=0)
    if frame.shape != (4, HEIGHT, WIDTH):
        sys.exit("bc_train: expected 240 x 320 images, got %s" % (rgb.shape,))
    return frame


# Image augmentation (--augment, issue 27): one draw per training window, the same for all its
# frames (a window is one scene seen for a few seconds). The ranges are training ranges: the
# held-out shifts of bc_evaluate --shift (light at 0.25, from the side, a blue or small target,
# a new floor) lie outside what the recorder's randomisation and this augmentation produce.
AUGMENT_BRIGHTNESS = (0.45, 1.5)  # RGB gain, log-uniform
AUGMENT_CHANNEL_GAIN = (0.85, 1.15)  # per colour channel, uniform
# Hue rotation [deg] of the whole frame about the grey axis, uniform. The recorder's target hues
# (-25 to 130 deg) then span -85 to 175 deg: the blue_target shift's 225 deg stays at least 45 deg
# (50 at full saturation) from every target hue training sees, on either side.
AUGMENT_HUE = (-60.0, 45.0)
AUGMENT_CONTRAST = (0.7, 1.3)  # about the window's mean, uniform
# Saturation: each pixel's colour moved toward its grey (the mean of its channels) by a factor
# drawn uniformly, and with probability AUGMENT_GREY the window turned grey. A target is then
# sometimes only weakly coloured or not at all, and the network has to find it by its shape and
# its disparity too, not by its hue alone (no hue is added: the blue_target shift stays unseen).
AUGMENT_SATURATION = (0.3, 1.0)
AUGMENT_GREY = 0.15
# Zoom [scale of the image about its centre], log-uniform, with the disparity values kept: a
# camera of another focal length, so that things look larger or smaller than they are while their
# disparity still says how far they are. The apparent size of a target stops telling its
# distance (the recorder's targets differ in size too; the small_target shift is smaller still).
AUGMENT_ZOOM = (0.8, 1.25)
# Uneven light: the brightness ramps across the frame in a random direction by a factor of up to
# exp(+-AUGMENT_SHADING) at its edges, and with probability AUGMENT_SHADOW_P a band across the frame
# (random direction, place and width) is darkened to AUGMENT_SHADOW of its brightness (a shadow
# cast by a light from low on one side; training's lights come from within 55 deg of straight
# down and cast short shadows).
AUGMENT_SHADING = 0.5
AUGMENT_SHADOW_P = 0.5
AUGMENT_SHADOW = (0.35, 0.8)
AUGMENT_NOISE = 0.03  # largest std of the pixel noise on RGB in [0, 1]
AUGMENT_SHIFT = 2  # largest sideways shift [px of the 60 x 80 frame] (camera pose)
# Largest vertical shift [px]: the camera pitched by up to 12 deg either way (the 60 rows span the
# 45 deg field of view). Things then appear higher or lower in the frame than the recorder's
# camera shows them, and a target near the robot may slide out of the frame's bottom edge while
# the expert keeps walking to it (what a camera mounted higher or a target lower than training's
# looks like).
AUGMENT_PITCH = 16
AUGMENT_DISPARITY_NOISE = 0.02  # std of the disparity noise (units of D = 32 px)
AUGMENT_DISPARITY_DROPOUT = 0.05  # largest share of disparity pixels lost (0: no match)

# --normalize-brightness: the mean RGB a frame is scaled to (the default room's frames average
# about 0.22 in [0, 1]), and what keeps a black frame finite.
REFERENCE_BRIGHTNESS = 0.22
BRIGHTNESS_FLOOR = 0.002
# --hue-blind: the colour every pixel's hue is turned to (the default target's, NavigationScene's
# SceneAppearance::target_rgb).
REFERENCE_HUE_RGB = (0.9, 0.12, 0.04)


def hue_direction(rgb):
    """The unit vector from the grey of `rgb` (the mean of its channels) to `rgb`: its hue, as a
    direction in the plane of colours with the same grey."""
    grey = sum(rgb) / 3.0
    c = [v - grey for v in rgb]
    norm = math.sqrt(sum(v * v for v in c))
    return [v / norm for v in c]


def hue_rotation(degrees):
    """The 3 x 3 matrix that turns RGB colours about the grey axis (1, 1, 1) by `degrees`: their
    hue moves by about that angle (red toward green for positive angles), brightness and
    saturation nearly kept; greys stay as they are."""
    a = math.radians(degrees)
    c, s = math.cos(a), math.sin(a)
    k = 1.0 / math.sqrt(3.0)
    skew = torch.tensor([[0.0, -k, k], [k, 0.0, -k], [-k, k, 0.0]])
    return c * torch.eye(3) + s * skew + (1.0 - c) * torch.full((3, 3), 1.0 / 3.0)


def uniform(low, high, generator=None, shape=()):
    """A tensor of `shape` drawn uniformly in [low, high] with `generator`."""
    return low + (high - low) * torch.rand(shape, generator=generator)


def log_uniform(low, high, generator=None):
    """A scalar tensor drawn log-uniformly in [low, high]."""
    return torch.exp(uniform(math.log(low), math.log(high), generator))


def zoom(rgb, disparity, scale):
    """Frames (F x 3 x H x W RGB, F x 1 x H x W disparity) enlarged by `scale` about the image's
    centre (below 1: made smaller, the border repeated), as by a camera of `scale` times the focal
    length; RGB interpolated bilinearly, the disparity sampled at the nearest pixel and its values
    kept (lost pixels stay 0, no new values appear)."""
    if scale == 1.0:
        return rgb, disparity
    theta = torch.tensor([[1.0 / scale, 0.0, 0.0], [0.0, 1.0 / scale, 0.0]])
    grid = F.affine_grid(theta.expand(rgb.shape[0], 2, 3), list(rgb.shape), align_corners=False)
    return (F.grid_sample(rgb, grid, mode="bilinear", padding_mode="border", align_corners=False),
            F.grid_sample(disparity, grid, mode="nearest", padding_mode="border",
                          align_corners=False))


def uneven_light(shape, generator=None):
    """A brightness factor (1 x 1 x H x W) for frames of `shape`: a ramp across the frame in a
    random direction (exp of up to +-AUGMENT_SHADING at the edges) times, with probability
    AUGMENT_SHADOW_P, a straight band of shadow (AUGMENT_SHADOW of the light) of random direction,
    place and width."""
    def draw(low, high):
        return float(uniform(low, high, generator))

    h, w = shape[-2], shape[-1]
    v = torch.linspace(-1.0, 1.0, h)[:, None].expand(h, w)
    u = torch.linspace(-1.0, 1.0, w)[None, :].expand(h, w)
    a = draw(0.0, 2.0 * math.pi)
    along = math.cos(a) * u + math.sin(a) * v  # in [-sqrt 2, sqrt 2]
    factor = torch.exp(draw(0.0, AUGMENT_SHADING) * along / math.sqrt(2.0))
    if draw(0.0, 1.0) < AUGMENT_SHADOW_P:
        b = draw(0.0, 2.0 * math.pi)
        across = math.cos(b) * u + math.sin(b) * v
        centre, half_width = draw(-1.0, 1.0), draw(0.1, 0.5)
        band = (across - centre).abs() < half_width
        factor = torch.where(band, factor * draw(*AUGMENT_SHADOW), factor)
    return factor[None, None]


def augment(window, generator=None):
    """A photometric and geometric variation of a window of frames (frames x 4 x H x W: RGB in
    [0, 1], then the scaled disparity), drawn with `generator` (torch.Generator, or torch's
    global one): a zoom (the disparity values kept); hue, brightness, uneven light and shadow,
    colour balance, contrast, saturation and pixel noise on RGB; a shift of the whole image (the
    camera's pitch and pose); noise and lost pixels on the disparity. Returns a new tensor."""
    def draw(low, high, shape=()):
        return uniform(low, high, generator, shape)

    x = window.clone().float()
    rgb, disparity = zoom(x[:, :3], x[:, 3:], float(log_uniform(*AUGMENT_ZOOM, generator)))
    turn = hue_rotation(float(draw(*AUGMENT_HUE)))
    rgb = torch.einsum("ij,fjhw->fihw", turn, rgb).clamp(0.0, 1.0)
    gain = log_uniform(*AUGMENT_BRIGHTNESS, generator) * draw(*AUGMENT_CHANNEL_GAIN, (1, 3, 1, 1))
    rgb = rgb * gain * uneven_light(rgb.shape, generator)
    mean = rgb.mean(dim=(1, 2, 3), keepdim=True)
    rgb = (rgb - mean) * draw(*AUGMENT_CONTRAST) + mean
    saturation = 0.0 if float(draw(0.0, 1.0)) < AUGMENT_GREY else draw(*AUGMENT_SATURATION)
    grey = rgb.mean(dim=1, keepdim=True)
    rgb = grey + saturation * (rgb - grey)
    rgb = rgb + draw(0.0, AUGMENT_NOISE) * torch.randn(rgb.shape, generator=generator)
    disparity = disparity + AUGMENT_DISPARITY_NOISE * torch.randn(disparity.shape,
                                                                   generator=generator)
    lost = torch.rand(disparity.shape, generator=generator) < draw(0.0, AUGMENT_DISPARITY_DROPOUT)
    disparity = torch.where(lost, torch.zeros_like(disparity), disparity.clamp(min=0.0))
    x = torch.cat([rgb.clamp(0.0, 1.0), disparity], dim=1)
    dy = int(torch.randint(-AUGMENT_PITCH, AUGMENT_PITCH + 1, (), generator=generator))
    dx = int(torch.randint(-AUGMENT_SHIFT, AUGMENT_SHIFT + 1, (), generator=generator))
    if dy or dx:  # shifted, the uncovered border repeats the edge
        x = torch.roll(x, shifts=(dy, dx), dims=(2, 3))
        if dy > 0:
            x[:, :, :dy] = x[:, :, dy:dy + 1]
        elif dy < 0:
            x[:, :, dy:] = x[:, :, dy - 1:dy]
        if dx > 0:
            x[:, :, :, :dx] = x[:, :, :, dx:dx + 1]
        elif dx < 0:
            x[:, :, :, dx:] = x[:, :, :, dx - 1:dx]
    return x


def read_index(folder, prefix=""):
    """Episodes of a folder's index.txt: {prefix + name: [(t, rgb, disparity, v_x, omega)]}."""
    path = os.path.join(folder, "index.txt")
    if not os.path.exists(path):
        sys.exit("bc_train: no index.txt in %s (record with examples/record_demonstrations)" % folder)
    episodes = {}
    for number, line in enumerate(open(path), 1):
        if not line.strip() or line.startswith("#"):
            continue
        fields = line.split()
        if len(fields) != 7:
            sys.exit("bc_train: %s:%d: expected 7 fields, got %d" % (path, number, len(fields)))
        rgb, disparity, episode = fields[:3]
        try:
            t, vx, vy, omega = (float(x) for x in fields[3:])
        except ValueError:
            sys.exit("bc_train: %s:%d: time and command must be numbers" % (path, number))
        if not all(math.isfinite(x) for x in (t, vx, vy, omega)):
            sys.exit("bc_train: %s:%d: non-finite time or command" % (path, number))
        episodes.setdefault(prefix + episode, []).append((t, folder, rgb, disparity, vx, omega))
    for frames in episodes.values():
        frames.sort()
    return episodes


def load_frames(folder, frames):
    """The processed frames of `frames` (rows of read_index), from the folder's cache when it
    holds them (keyed by the image names), else from the PNG files (and then cached)."""
    cache = os.path.join(folder, "bc_frames_60x80.npy")
    names = os.path.join(folder, "bc_frames_60x80.txt")
    wanted = [f[2] for f in frames]
    if os.path.exists(cache) and os.path.exists(names):
        cached = open(names).read().split()
        if set(wanted) <= set(cached):
            data = np.load(cache, mmap_mode="r")
            where = {n: i for i, n in enumerate(cached)}
            return [np.asarray(data[where[n]], dtype=np.float32) for n in wanted]
    out = [load_frame(folder, f[2], f[3]) for f in frames]
    # written atomically (each to a temporary name, then renamed), the names last: a run
    # interrupted here leaves the old cache or none, never names that do not match the frames
    if os.path.exists(names):
        os.remove(names)
    with open(cache + ".tmp", "wb") as f:
        np.save(f, np.stack(out).astype(np.float16))
    os.replace(cache + ".tmp", cache)
    with open(names + ".tmp", "w") as f:
        f.write("\n".join(wanted) + "\n")
    os.replace(names + ".tmp", names)
    return out


class Chunks(torch.utils.data.Dataset):
    """Windows of `chunk` consecutive frames of one episode (its first frame repeated
    sequence - 1 times in front) with the command after each of the last chunk - sequence + 1
    frames, which then end a full sequence; a mask marks the ones past the episode's end.
    Consecutive windows overlap by sequence - 1 frames, so that every frame is a target once."""

    def __init__(self, episodes, frames, sequence, chunk, augmented=False):
        """episodes: lists of rows of read_index; frames: {(folder, rgb): processed frame};
        augmented: each window drawn through augment()."""
        self.augmented = augmented
        self.frames, self.labels, self.items = [], [], []
        stride = chunk - sequence + 1
        for rows in episodes:
            start = len(self.frames)
            for _, folder, rgb, _, vx, omega in [rows[0]] * (sequence - 1) + rows:
                self.frames.append(torch.from_numpy(frames[(folder, rgb)]))
                self.labels.append(torch.tensor([vx / MAX_COMMAND[0], omega / MAX_COMMAND[1]],
                                                dtype=torch.float32).clamp(-1.0, 1.0))
            end = len(self.frames)
            s = start
            while True:
                ids = [min(i, end - 1) for i in range(s, s + chunk)]  # the last frame repeats
                mask = torch.tensor([1.0 if s + k < end else 0.0
                                     for k in range(sequence - 1, chunk)])
                self.items.append((ids, mask))
                if s + chunk >= end:
                    break
                s += stride
        self.sequence = sequence

    def targets(self):
        return sum(int(m.sum().item()) for _, m in self.items)

    def __len__(self):
        return len(self.items)

    def __getitem__(self, i):
        ids, mask = self.items[i]
        window = torch.stack([self.frames[j] for j in ids])
        return (augment(window) if self.augmented else window,
                torch.stack([self.labels[j] for j in ids[self.sequence - 1:]]), mask)


def block(inputs, outputs):
    """Two 3 x 3 convolutions, each batch-normalised (without it, most ReLUs of a small
    network died within the first steps and the encoder gave every frame the same features)."""
    return nn.Sequential(nn.Conv2d(inputs, outputs, 3, padding=1, bias=False),
                         nn.BatchNorm2d(outputs), nn.ReLU(inplace=True),
                         nn.Conv2d(outputs, outputs, 3, padding=1, bias=False),
                         nn.BatchNorm2d(outputs), nn.ReLU(inplace=True))


class UNetLstm(nn.Module):
    """Figure 11.2: a U-Net (two poolings, skip connections by concatenation) per frame, a
    fully connected layer, an LSTM over the sequence, and a tanh regression of (v_x, omega_z)."""

    def __init__(self, width=16, hidden=64, sequence=5, normalize_brightness=False,
                 hue_blind=False):
        super().__init__()
        self.normalize_brightness = normalize_brightness
        self.hue_blind = hue_blind
        self.reference_hue = hue_direction(REFERENCE_HUE_RGB)  # List[float] for TorchScript
        self.reference_brightness = REFERENCE_BRIGHTNESS  # attributes: TorchScript keeps them
        self.brightness_floor = BRIGHTNESS_FLOOR
        w = width
        self.down1, self.down2, self.bottom = block(4, w), block(w, 2 * w), block(2 * w, 4 * w)
        self.up2, self.up1 = block(6 * w, 2 * w), block(3 * w, w)
        self.pool = nn.MaxPool2d(2)
        self.upsample = nn.Upsample(scale_factor=2.0, mode="bilinear", align_corners=False)
        self.squeeze = nn.Sequential(nn.Conv2d(w, 8, 1), nn.AdaptiveAvgPool2d((6, 8)))
        self.fc = nn.Sequential(nn.Linear(8 * 6 * 8, hidden), nn.ReLU(inplace=True))
        self.lstm = nn.LSTM(hidden, hidden, batch_first=True)
        self.out = nn.Linear(hidden, 2)
        self.hidden = hidden
        self.sequence = sequence

    @torch.jit.export
    def encode(self, x):
        """Frames (N, 4, 60, 80) -> features (N, hidden)."""
        if self.normalize_brightness:
            rgb = x[:, :3]
            mean = rgb.mean(dim=(1, 2, 3), keepdim=True)
            scale = self.reference_brightness / (mean + self.brightness_floor)
            x = torch.cat([rgb * scale, x[:, 3:]], dim=1)
        if self.hue_blind:
            rgb = x[:, :3]
            grey = rgb.mean(dim=1, keepdim=True)
            chroma = torch.sqrt(((rgb - grey) ** 2).sum(dim=1, keepdim=True) + 1e-12)
            hue = torch.tensor(self.reference_hue, dtype=x.dtype, device=x.device).view(1, 3, 1, 1)
            x = torch.cat([grey + chroma * hue, x[:, 3:]], dim=1)
        d1 = self.down1(x)
        d2 = self.down2(self.pool(d1))
        b = self.bottom(self.pool(d2))
        u2 = self.up2(torch.cat([self.upsample(b), d2], dim=1))
        u1 = self.up1(torch.cat([self.upsample(u2), d1], dim=1))
        return self.fc(torch.flatten(self.squeeze(u1), 1))

    @torch.jit.export
    def head(self, features):
        """Sequences of features (N, T, hidden), oldest first -> (N, 2) in [-1, 1]: the command
        after the latest frame, the LSTM starting from a zero state."""
        y, _ = self.lstm(features)
        return torch.tanh(self.out(y[:, -1]))

    def forward(self, x):
        """Sequences x (B, T, 4, 60, 80) -> (B, 2), the command after the latest frame."""
        b, t = x.shape[0], x.shape[1]
        return self.head(self.encode(x.reshape(b * t, 4, x.shape[3], x.shape[4])).reshape(b, t, -1))

    def forward_chunks(self, x):
        """Windows x (B, C, 4, 60, 80) -> (B, C - sequence + 1, 2): the command after each
        frame that ends a full sequence, each frame encoded once."""
        b, c = x.shape[0], x.shape[1]
        features = self.encode(x.reshape(b * c, 4, x.shape[3], x.shape[4])).reshape(b, c, -1)
        n = c - self.sequence + 1
        windows = features.unfold(1, self.sequence, 1)  # (B, n, hidden, sequence)
        windows = windows.permute(0, 1, 3, 2).reshape(b * n, self.sequence, self.hidden)
        return self.head(windows).reshape(b, n, 2)


def histograms(truth, prediction, out, bins):
    """Per velocity: histograms (bins), KL(truth || prediction) (eq. 11.1), entropies (eq. 9.1)."""
    rows = []
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.6))
    for k, (name, unit) in enumerate((("v_x", "m/s"), ("omega_z", "rad/s"))):
        edges = bins[k]
        p = np.histogram(truth[:, k], bins=edges)[0].astype(float)
        q = np.histogram(prediction[:, k], bins=edges)[0].astype(float)
        p, q = p / p.sum(), q / q.sum()
        eps = 1e-6  # empty predicted bins: the divergence stays finite
        kl = float(np.sum(p * np.log((p + eps) / (q + eps))))
        entropy = lambda d: float(-np.sum(d[d > 0] * np.log(d[d > 0])))
        rows.append((name, kl, entropy(p), entropy(q)))
        centres = 0.5 * (edges[1:] + edges[:-1])
        width = edges[1] - edges[0]
        axes[k].bar(centres, p, width=width, alpha=0.6, label="ground truth")
        axes[k].bar(centres, q, width=width, alpha=0.6, label="prediction")
        axes[k].set_xlabel("%s [%s]" % (name, unit))
        axes[k].set_title("KL %.3f, entropy %.2f / %.2f" % (kl, entropy(p), entropy(q)))
        axes[k].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "histograms.png"), dpi=100)
    plt.close(fig)
    with open(os.path.join(out, "histograms.csv"), "w") as f:
        f.write("velocity,kl_divergence,entropy_truth,entropy_prediction\n")
        for r in rows:
            f.write("%s,%.6f,%.6f,%.6f\n" % r)
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("data", nargs="+", help="folders with index.txt (recordings, DAgger)")
    parser.add_argument("out")
    parser.add_argument("--epochs", type=int, default=30)
    parser.add_argument("--batch", type=int, default=32)
    parser.add_argument("--lr", type=float, default=1e-3)
    parser.add_argument("--sequence", type=int, default=5)
    parser.add_argument("--chunk", type=int, default=16)
    parser.add_argument("--width", type=int, default=8)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--max-steps", type=int, default=0, help="stop after N optimiser steps")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--augment", action="store_true",
                        help="vary the training windows' zoom, hue, brightness, uneven light and "
                        "shadow, colour balance, contrast, saturation, noise, position, camera "
                        "pitch and disparity (augment(); validation stays as recorded)")
    parser.add_argument("--init", help="start from these weights (OUT/best.pth of an earlier "
                        "run, e.g. to fine-tune after a DAgger round); with --epochs 0 only "
                        "evaluate and export them")
    parser.add_argument("--normalize-brightness", action="store_true",
                        help="scale each frame's RGB to a mean of %.2f inside the network (the "
                        "exported model does it too): features independent of the light's "
                        "intensity; give it again when fine-tuning such a model with --init"
                        % REFERENCE_BRIGHTNESS)
    parser.add_argument("--hue-blind", action="store_true",
                        help="turn every pixel's colour to one hue inside the network (the "
                        "exported model does it too), keeping its grey level and strength: "
                        "features independent of the target's hue; give it again when "
                        "fine-tuning such a model with --init")
    args = parser.parse_args()
    if args.epochs < (0 if args.init else 1) or args.batch < 1 or args.sequence < 1 \
            or not args.lr > 0:
        sys.exit("bc_train: epochs (0 only with --init), batch, sequence >= 1 and lr > 0 expected")
    if args.chunk < args.sequence:
        sys.exit("bc_train: --chunk must be at least --sequence")
    torch.manual_seed(args.seed)
    random.seed(args.seed)
    np.random.seed(args.seed)
    torch.set_num_threads(args.threads)
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "command.txt"), "w") as f:  # how this model was made
        f.write(" ".join(shlex.quote(a) for a in [sys.executable] + sys.argv) + "\n")

    episodes = {}
    for i, folder in enumerate(args.data):
        episodes.update(read_index(folder, "%d/" % i if len(args.data) > 1 else ""))
    frames = {}
    for folder in args.data:
        rows = [r for e in episodes.values() for r in e if r[1] == folder]
        print("bc_train: loading %d frames of %s" % (len(rows), folder), flush=True)
        for r, f in zip(rows, load_frames(folder, rows)):
            frames[(folder, r[2])] = f
    # An episode's split follows from its name alone (CRC-32 mod 10 == 0: validation), so it
    # stays the same when folders are added (DAgger rounds) or a run starts from --init.
    names = sorted(episodes)
    val_names = [n for n in names if zlib.crc32(n.split("/", 1)[-1].encode()) % 10 == 0]
    if not val_names and len(names) > 1:
        val_names = names[:1]
    train_names = [n for n in names if n not in val_names]
    if not train_names:
        sys.exit("bc_train: need at least one training episode")
    train = Chunks([episodes[n] for n in train_names], frames, args.sequence, args.chunk,
                   augmented=args.augment)
    val = Chunks([episodes[n] for n in val_names or train_names], frames, args.sequence,
                 args.chunk)
    print("bc_train: %d episodes (%d targets) for training, %d (%d targets) for validation"
          % (len(train_names), train.targets(), len(val_names), val.targets()), flush=True)
    batch = max(1, args.batch // (args.chunk - args.sequence + 1))  # windows ~ args.batch targets
    loader = torch.utils.data.DataLoader(train, batch_size=batch, shuffle=True)
    val_loader = torch.utils.data.DataLoader(val, batch_size=8)

    model = UNetLstm(args.width, sequence=args.sequence,
                     normalize_brightness=args.normalize_brightness, hue_blind=args.hue_blind)
    if args.init:
        try:
            model.load_state_dict(torch.load(args.init))
        except (OSError, RuntimeError) as e:
            sys.exit("bc_train: --init %s: %s (same --width and --sequence?)" % (args.init, e))
    optimiser = torch.optim.Adam(model.parameters(), lr=args.lr)
    best, steps, log = math.inf, 0, []

    def loss_fn(prediction, label, mask):
        """MSE over the counted frames (mask 1)."""
        squared = ((prediction - label) ** 2).mean(dim=2) * mask
        return squared.sum() / mask.sum().clamp(min=1.0)

    def evaluate():
        model.eval()
        total, n, truth, pred = 0.0, 0, [], []
        with torch.no_grad():
            for x, y, m in val_loader:
                p = model.forward_chunks(x)
                total += loss_fn(p, y, m).item() * m.sum().item()
                n += m.sum().item()
                keep = m.numpy() > 0.5
                truth.append(y.numpy()[keep])
                pred.append(p.numpy()[keep])
        model.train()
        return total / n, np.concatenate(truth), np.concatenate(pred)

    start = time.time()
    for epoch in range(1, args.epochs + 1):
        total, n = 0.0, 0
        for x, y, m in loader:
            optimiser.zero_grad()
            loss = loss_fn(model.forward_chunks(x), y, m)
            loss.backward()
            optimiser.step()
            total += loss.item() * m.sum().item()
            n += m.sum().item()
            steps += 1
            if args.max_steps and steps >= args.max_steps:
                break
        val_loss, _, _ = evaluate()
        log.append((epoch, total / n, val_loss, time.time() - start))
        marker = ""
        if val_loss < best:  # export now: a long run stopped early keeps its best model
            best = val_loss
            torch.save(model.state_dict(), os.path.join(args.out, "best.pth"))
            model.eval()
            torch.jit.script(model).save(os.path.join(args.out, "model.pt"))
            model.train()
            marker = " (best)"
        print("epoch %3d: train MSE %.4f, validation MSE %.4f, %.0f s%s"
              % (epoch, total / n, val_loss, time.time() - start, marker), flush=True)
        if args.max_steps and steps >= args.max_steps:
            break

    if not log:  # --epochs 0: the given weights
        torch.save(model.state_dict(), os.path.join(args.out, "best.pth"))
        best, _, _ = evaluate()
        model.eval()
        torch.jit.script(model).save(os.path.join(args.out, "model.pt"))
    model.load_state_dict(torch.load(os.path.join(args.out, "best.pth")))
    model.eval()
    with open(os.path.join(args.out, "training_log.csv"), "w") as f:
        f.write("epoch,train_mse,validation_mse,seconds\n")
        for row in log:
            f.write("%d,%.6f,%.6f,%.1f\n" % row)
    _, truth, pred = evaluate()
    truth = truth * np.array(MAX_COMMAND)
    pred = pred * np.array(MAX_COMMAND)
    # The thesis's bins (§9.2): 0.01 m/s and 0.01 rad/s, centred on zero.
    bins = (np.arange(-0.045, 0.0451, 0.01), np.arange(-0.085, 0.0851, 0.01))
    rows = histograms(truth, pred, args.out, bins)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 3.6))
    ax.plot([r[0] for r in log], [r[1] for r in log], label="training")
    ax.plot([r[0] for r in log], [r[2] for r in log], label="validation")
    ax.set_xlabel("epoch")
    ax.set_ylabel("MSE (normalised commands)")
    ax.set_yscale("log")
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "training.png"), dpi=100)
    for name, kl, ht, hp in rows:
        print("bc_train: %s: KL divergence %.3f, entropy truth %.2f, prediction %.2f"
              % (name, kl, ht, hp))
    print("bc_train: best validation MSE %.4f; wrote %s" % (best, os.path.join(args.out, "model.pt")))


if __name__ == "__main__":
    main()
