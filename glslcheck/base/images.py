"""Images on disk: the one place that quantises, writes and reads the pictures glslcheck makes
(renders of either backend, GIF animations, diff heat maps, bench plots).

- `quantise(img)`: float RGBA -> 8-bit, as a display shows it: NaN as 0, clamped to [0, 1],
  `floor(v * 255 + 0.5)`.
- `save_image(img, path)`: `.npy` keeps the float32 array unclamped; `.png` is quantised RGBA.
- `GifWriter`: an animation written one frame at a time (a frame is quantised, converted to a
  256-colour palette of its own and encoded when it is added; nothing of it is kept), so
  `render --frames 1000 --size 1920x1080` needs the memory of one frame, not of a thousand.
- `atomic_write(path)`: every file is written to a temporary file in the same folder and renamed
  over `path` only when complete, so an error or Ctrl-C halfway leaves the old file as it was
  (and no partial file behind).
- `check_output(path, suffixes, what)`: refuses, before any work, a file name whose extension
  is not one of the formats the writer makes (`verify --diff bad`, `bench --plot x.xyz`).
- `load_image(path)`: a `.npy` float array or an image file as float32 RGBA in [0, 1].
- `thumbnail(img)`, `png_bytes(rgb)`: a render scaled down as the screen shows it, and PNG bytes
  of an 8-bit image (pages inline them as data URIs).

Write errors come back as `InputError` (exit 2) naming the path and the reason.
"""

from __future__ import annotations

import contextlib
import io
import os
import stat
import tempfile
from collections.abc import Iterator
from pathlib import Path

import numpy as np

from .diagnostics import InputError

IMAGE_SUFFIXES = (".png", ".npy")


def quantise(img: np.ndarray) -> np.ndarray:
    """8-bit values of a float image (any channel count): NaN as 0, clamped, *255 + 0.5 floored."""
    with np.errstate(invalid="ignore"):
        return np.floor(np.clip(np.nan_to_num(img, nan=0.0), 0.0, 1.0) * 255.0 + 0.5).astype(
            np.uint8
        )


def check_output(path: str | os.PathLike, suffixes: tuple[str, ...], what: str) -> None:
    """InputError unless `path` ends in one of `suffixes` (compared case-insensitively)."""
    if not str(path).lower().endswith(suffixes):
        names = " or ".join(suffixes)
        raise InputError(
            f"{path}: error: the {what} must be a {names} file (name it e.g. out{suffixes[0]})"
        )


def _mode_for_new_files() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask


@contextlib.contextmanager
def atomic_write(path: str | os.PathLike, what: str = "file") -> Iterator[str]:
    """Yield a temporary file name next to `path`; rename it over `path` when the block ends
    without an exception, remove it otherwise (also on KeyboardInterrupt). An OSError while
    writing becomes InputError("<path>: error: cannot write the <what> (<reason>)").

    A symbolic link is written through (its target is replaced); a path that is not a regular
    file (/dev/null, a FIFO) is written directly, never replaced. The file gets the mode the
    old one had, or a new file's mode (0666 less the umask)."""
    target = Path(os.path.realpath(path))
    try:
        old = os.stat(target)
    except OSError:
        old = None
    if old is not None and not stat.S_ISREG(old.st_mode):
        try:
            yield str(path)
        except OSError as e:
            raise InputError(
                f"{path}: error: cannot write the {what} ({e.strerror or e})"
            ) from None
        return
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=target.parent)
        os.close(fd)
    except OSError as e:
        raise InputError(f"{path}: error: cannot write the {what} ({e.strerror or e})") from None
    done = False
    try:
        yield tmp
        os.chmod(tmp, stat.S_IMODE(old.st_mode) if old is not None else _mode_for_new_files())
        os.replace(tmp, target)
        done = True
    except OSError as e:
        raise InputError(f"{path}: error: cannot write the {what} ({e.strerror or e})") from None
    finally:
        if not done:
            with contextlib.suppress(OSError):
                os.unlink(tmp)


def save_image(img: np.ndarray, path: str | os.PathLike) -> None:
    """`.npy`: the float32 array; otherwise an 8-bit RGBA image in the format the extension
    names."""
    with atomic_write(path, "image") as tmp:
        if str(path).lower().endswith(".npy"):
            buffer = io.BytesIO()  # np.save seeks: write it whole, so a pipe can take it too
            np.save(buffer, np.asarray(img, dtype=np.float32))
            with open(tmp, "wb") as f:
                f.write(buffer.getbuffer())
            return
        from PIL import Image

        Image.fromarray(quantise(img), "RGBA").save(tmp, format=_pil_format(path))


def save_rgb(rgb: np.ndarray, path: str | os.PathLike, what: str = "image") -> None:
    """An 8-bit RGB array (a diff heat map, a plot) as an image file, atomically."""
    from PIL import Image

    save_pil(Image.fromarray(rgb), path, what)


def save_pil(image, path: str | os.PathLike, what: str = "image") -> None:
    """A PIL image, atomically, in the format the extension names."""
    with atomic_write(path, what) as tmp:
        image.save(tmp, format=_pil_format(path))


def _pil_format(path: str | os.PathLike) -> str:
    from PIL import Image

    Image.init()
    fmt = Image.EXTENSION.get(Path(path).suffix.lower())
    if fmt is None:
        raise InputError(
            f"{path}: error: no image format has the extension {Path(path).suffix or '(none)'!r}"
        )
    return fmt


def load_image(path: str | os.PathLike) -> np.ndarray:
    """A `.npy` array as it was saved, or an image file as float32 RGBA in [0, 1]."""
    if str(path).lower().endswith(".npy"):
        return np.load(path, allow_pickle=False)
    from PIL import Image

    with Image.open(path) as im:
        return np.asarray(im.convert("RGBA"), dtype=np.float32) / 255.0


class GifWriter:
    """A looping GIF animation written frame by frame (see the module docstring).

    with GifWriter("anim.gif", fps=30) as gif:
        for img in frames:
            gif.add(img)          # float RGB(A) image, row 0 at the top

    The file appears (atomically) when the block ends without an exception.
    """

    def __init__(self, path: str | os.PathLike, fps: float):
        self.path = path
        self.duration = max(
            int(round(1000 / fps)), 10
        )  # ms; GIF counts in 1/100 s, browsers floor to 10 ms
        self.frames = 0
        self._atomic: contextlib.AbstractContextManager[str] | None = None
        self._file: io.BufferedWriter | None = None  # open between __enter__ and __exit__

    def __enter__(self) -> GifWriter:
        check_output(self.path, (".gif",), "animation")
        self._atomic = atomic = atomic_write(self.path, "animation")
        tmp = atomic.__enter__()
        try:
            self._file = open(tmp, "wb")
        except OSError as e:
            atomic.__exit__(type(e), e, e.__traceback__)
            raise InputError(
                f"{self.path}: error: cannot write the animation ({e.strerror or e})"
            ) from None
        return self

    def add(self, img: np.ndarray) -> None:
        from PIL import GifImagePlugin, Image

        frame = Image.fromarray(quantise(img[..., :3]), "RGB").convert(
            "P", palette=Image.Palette.ADAPTIVE
        )
        try:
            if self.frames == 0:
                header, _ = GifImagePlugin.getheader(
                    frame, None, {"loop": 0, "duration": self.duration}
                )
            else:
                GifImagePlugin.getheader(frame, None, {})  # puts the frame's palette in GIF form
                header = []
            # Each frame carries its own colour table (the first one's is also the global one).
            data = GifImagePlugin.getdata(frame, duration=self.duration, include_color_table=True)
            assert self._file is not None, "GifWriter.add outside its with block"
            self._file.write(b"".join(bytes(b) for b in (*header, *data)))
        except OSError as e:
            raise InputError(
                f"{self.path}: error: cannot write the animation ({e.strerror or e})"
            ) from None
        self.frames += 1

    def __exit__(self, kind, error, tb) -> None:
        atomic, self._atomic = self._atomic, None
        assert atomic is not None and self._file is not None, "__exit__ without __enter__"
        try:
            if error is None:
                if not self.frames:
                    raise InputError(f"{self.path}: error: an animation needs at least one frame")
                self._file.write(b";")  # the GIF trailer
            self._file.close()
        except BaseException as e:
            self._file.close()
            atomic.__exit__(type(e), e, e.__traceback__)
            raise
        atomic.__exit__(kind, error, tb)


THUMBNAIL_WIDTH = 160  # a grades page shows a row of these per team: small, still readable


def thumbnail(img: np.ndarray, width: int = THUMBNAIL_WIDTH) -> np.ndarray:
    """8-bit RGB of a float render as the screen shows it (`quantise`), scaled down to `width`
    pixels across (aspect kept; never scaled up) by averaging the pixels each one covers."""
    from PIL import Image

    rgb = quantise(np.asarray(img)[..., :3])
    h, w = rgb.shape[:2]
    if w <= width:
        return rgb
    height = max(1, round(h * width / w))
    return np.asarray(Image.fromarray(rgb, "RGB").resize((width, height), Image.Resampling.BOX))


def png_bytes(rgb: np.ndarray) -> bytes:
    """An 8-bit RGB array as the bytes of a PNG file (for pages that inline their images), at
    zlib's default level: `optimize` would make a thumbnail a few percent smaller for several
    times the encoding time, which a page of a whole class pays per image."""
    from PIL import Image

    buffer = io.BytesIO()
    Image.fromarray(rgb).save(buffer, format="PNG")
    return buffer.getvalue()
