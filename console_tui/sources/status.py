"""What a source reports about itself, for the status bar."""

from __future__ import annotations

from dataclasses import dataclass

from ..model.levels import severity_name

#: ``path_note`` while the take loop in C is being built (rclpy takes meanwhile).
PATH_NOTE_BUILDING = "being built (taken through rclpy meanwhile)"


@dataclass
class SourceStatus:
    """A snapshot of a live source's state, replaced (not mutated) by the source thread."""

    topic: str = ""
    publishers: int = 0
    #: Which ROS and where, for example ``ROS 1 http://robot:11311/`` or ``ROS 2 domain 7``.
    origin: str = ""
    #: Why this ROS and not the other, when the user may have expected the other, or "": for
    #: example that no ROS 1 master answered at ``ROS_MASTER_URI``.
    remark: str = ""
    #: How messages are taken and decoded, for example ``raw+cdr`` or ``typed``.
    path: str = ""
    #: Why the path is not the fastest there is, or "": for example why the take loop in C
    #: (``c+cdr``) is not used (``no C compiler (cc)``).
    path_note: str = ""
    #: Messages known lost, all causes: the sum of the ``lost_*`` counts below.
    lost: int = 0
    #: Lost in the middleware (for example a publisher's history overwritten before the
    #: console read it): as its message-lost events report, or as the gaps in each
    #: publisher's sequence numbers show, whichever is more. Kept after publishers leave.
    lost_qos: int = 0
    #: Dropped because the UI fell behind and the intake queue was full.
    lost_queue: int = 0
    #: Messages that neither the direct decoder nor rclpy could read.
    lost_undecodable: int = 0
    #: Messages the direct decoder refused and rclpy's deserializer read instead.
    decoded_by_rclpy: int = 0
    #: Publishers on the topic whose QoS no subscription of the console can match.
    incompatible: int = 0
    #: A one-line problem the user should see, or "".
    problem: str = ""
    running: bool = False
    #: The robot this source reads, when the console reads a fleet (``ros.fleet``), else "".
    robot: str = ""
    #: What the table says while this source has given nothing, for a source that reads no ROS
    #: topic (the journal, a launch's output): ``following this machine's journal: no entries yet…``.
    hint: str = ""
    #: Whether ``path`` is progress (a log warehouse's ``1,000 rows read, following``): a detail
    #: the status line gives up first, as it does a take path.
    path_is_progress: bool = False
    #: The lowest severity taken (``tail --level``; 0: every message).
    min_level: int = 0
    #: Why the middleware does not drop what is below ``min_level`` (the intake then drops it
    #: itself), or "" (a DDS content filter drops it before it is sent).
    level_filter_note: str = ""

    @property
    def state(self) -> str:
        """In a word: ``problem``, ``receiving`` (publishers are there), ``waiting`` or ``starting``."""
        if self.problem:
            return "problem"
        if self.publishers:
            return "receiving"
        return "waiting" if self.running else "starting"

    def path_text(self) -> str:
        """How messages are taken, in words: ``c+cdr: the take loop in C, the CDR decoded directly``."""
        meaning = _PATHS.get(self.path, "")
        return f"{self.path}: {meaning}" if meaning else self.path

    def slow_path_text(self) -> str:
        """What is lost on the slower intake path (no loop in C), said once at start; "" on
        the fast path (or where there is no faster one)."""
        slow = _SLOW_PATHS.get(self.path)
        if not self.path_note or self.path_note == PATH_NOTE_BUILDING or slow is None:
            return ""  # the fast path, on its way or in use (the note says how it was built)
        return (
            f"slower intake: {self.loop_name()} is not used ({self.path_note}): {slow} the CPU a "
            "message, so high rates are kept up with less well. The fast path needs a C compiler "
            "(cc) and Python's headers (python3-dev)."
        )

    def level_filter_text(self) -> str:
        """Where messages below ``min_level`` are dropped, in words; "" without a lowest severity."""
        if not self.min_level:
            return ""
        words = f"level >= {severity_name(self.min_level)}"
        if not self.level_filter_note:
            return f"{words}: asked of DDS (a content filter: what is below is never sent here)"
        return f"{words}: filtered by the intake, not by the middleware ({self.level_filter_note})"

    def loop_name(self) -> str:
        """The loop in C of this source's intake: ``the take loop in C`` (ROS 2) or ``the frame
        loop in C`` (ROS 1)."""
        return "the frame loop in C" if self.path in ("c+tcpros", "tcpros") else "the take loop in C"

    @property
    def take_path(self) -> bool:
        """Whether ``path`` says how messages are taken (``c+cdr``...), a detail, rather than
        what the source is (``demo: 4 nodes``, ``starting``)."""
        return self.path in _PATHS

    def loss_text(self) -> str:
        """The loss for a status bar: "" when nothing was lost, else the total and its causes."""
        if not self.lost:
            return ""
        causes = [
            (self.lost_qos, "in the middleware"),
            (self.lost_queue, "UI behind"),
            (self.lost_undecodable, "unreadable"),
        ]
        detail = ", ".join(f"{count:,} {cause}" for count, cause in causes if count)
        return f"{self.lost:,} lost ({detail})"


#: What the slower path costs, for each path slower than one with a loop in C.
_SLOW_PATHS = {"raw+cdr": "rclpy's take costs 2-3 times", "tcpros": "Python's decoder costs about twice"}

#: What each ``path`` means.
_PATHS = {
    "c+cdr": "the take loop in C, the CDR decoded directly",
    "raw+cdr": "rclpy's take, the CDR decoded directly",
    "typed": "rclpy's take and typed messages",
    "tcpros": "ROS 1's TCPROS, read directly",
    "c+tcpros": "ROS 1's TCPROS, read directly, decoded in C",
}
