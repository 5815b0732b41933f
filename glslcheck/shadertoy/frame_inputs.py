"""One frame's inputs (`FrameInputs`) and the `@frame_inputs` decorator every backend's `render`
takes them through. Apart from shadertoy/wrapper.py because `FrameInputs` is a dataclass (it needs
`__post_init__` and `dataclasses.fields`): importing `dataclasses` would cost every `glslcheck
lint`, which never renders.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, fields
from typing import Any

from .wrapper import DEFAULT_SIZE, frame_uniforms, sample_offsets


@dataclass(frozen=True)
class FrameInputs:
    """One frame's inputs, the arguments every backend's `render` takes: the size (width,
    height), the values of iTime, iFrame, iMouse, iDate, iTimeDelta and iFrameRate, and the
    samples per pixel. Checked when made: ValueError for a size under 1x1 or a sample count
    that is not a square. A backend's render declares them once with `@frame_inputs`."""

    size: tuple[int, int] = DEFAULT_SIZE
    time: float = 0.0
    frame: int = 0
    mouse: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0)
    date: Any = None  # a datetime, a 4-tuple or None (`as_date`)
    time_delta: float = 1.0 / 60.0
    frame_rate: float = 60.0
    samples: int = 1

    def __post_init__(self) -> None:
        if self.width < 1 or self.height < 1:
            raise ValueError(f"size must be at least 1x1, not {self.width}x{self.height}")
        sample_offsets(self.samples)

    @property
    def width(self) -> int:
        return int(self.size[0])

    @property
    def height(self) -> int:
        return int(self.size[1])

    @property
    def offsets(self) -> list[tuple[float, float]]:
        return sample_offsets(self.samples)

    def uniforms(self) -> dict:
        """`frame_uniforms` of this frame."""
        return frame_uniforms(
            self.width,
            self.height,
            self.time,
            self.frame,
            self.mouse,
            self.date,
            self.time_delta,
            self.frame_rate,
        )

    def keywords(self) -> dict:
        """The inputs as keyword arguments of a render."""
        return {f.name: getattr(self, f.name) for f in fields(self)}


def frame_inputs(render: Callable) -> Callable:
    """A backend's `render(self, inputs: FrameInputs, <its own options>)` called as
    `render(size=..., time=..., ..., samples=..., <its own options>)`: the inputs are declared
    once, in FrameInputs, and the signature that `inspect.signature` and `help()` show (verify
    reads which arguments each backend takes from it) is FrameInputs' fields, then the options."""
    import functools
    import inspect

    own = list(inspect.signature(render).parameters.values())
    fed = [
        inspect.Parameter(
            f.name, inspect.Parameter.POSITIONAL_OR_KEYWORD, default=f.default, annotation=f.type
        )
        for f in fields(FrameInputs)
    ]
    signature = inspect.Signature(
        [own[0], *fed, *own[2:]], return_annotation=inspect.signature(render).return_annotation
    )
    names = [p.name for p in fed]

    @functools.wraps(render)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        given = signature.bind(*args, **kwargs).arguments  # TypeError for an unknown argument
        inputs = FrameInputs(**{name: given.pop(name) for name in names if name in given})
        return render(given.pop(own[0].name), inputs, **given)

    # (inspect.signature reads it; typeshed gives functions no such attribute)
    wrapper.__signature__ = signature  # type: ignore[attr-defined]
    return wrapper
