"""Where the tools find the project's build and the shared expression judge."""
import os

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def add_facial_and_judge(ap, judge_flag="--judge"):
    """The --facial (build/bin/facial) and judge (../shared/judge/fer_judge.py) options."""
    ap.add_argument("--facial", default=os.path.join(ROOT, "build", "bin", "facial"))
    ap.add_argument(judge_flag, default=os.path.join(os.path.dirname(ROOT), "shared", "judge", "fer_judge.py"))
