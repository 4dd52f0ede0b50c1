"""Re-evaluate drives frame by frame with the safety engines and collect the verdicts."""

from workbench.evaluate.pipeline import EngineRunner, FrameResult, evaluate_frames
from workbench.evaluate.violations import Violation, detect_violations

__all__ = ["EngineRunner", "FrameResult", "Violation", "detect_violations", "evaluate_frames"]
