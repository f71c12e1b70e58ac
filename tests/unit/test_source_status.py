"""What the status bar says about loss."""

from console_tui.sources.status import SourceStatus


def test_no_loss_says_nothing():
    assert SourceStatus().loss_text() == ""


def test_loss_names_its_causes():
    status = SourceStatus(lost=1_234, lost_qos=1_200, lost_queue=0, lost_undecodable=34)
    assert status.loss_text() == "1,234 lost (1,200 in the middleware, 34 unreadable)"


def test_the_path_in_words():
    assert SourceStatus(path="c+cdr").path_text() == "c+cdr: the take loop in C, the CDR decoded directly"
    assert SourceStatus(path="raw+cdr").path_text() == "raw+cdr: rclpy's take, the CDR decoded directly"
    assert SourceStatus(path="tcpros").path_text() == "tcpros: ROS 1's TCPROS, read directly"
    assert SourceStatus(path="c+tcpros").path_text() == "c+tcpros: ROS 1's TCPROS, read directly, decoded in C"
    assert SourceStatus(path="starting").path_text() == "starting"


def test_the_slower_path_is_not_said_while_the_loop_is_built_or_when_it_is_in_use():
    from console_tui.sources.status import PATH_NOTE_BUILDING

    assert SourceStatus(path="raw+cdr", path_note=PATH_NOTE_BUILDING).slow_path_text() == ""
    assert SourceStatus(path="c+cdr", path_note="built into a private directory, as X").slow_path_text() == ""
    assert SourceStatus(path="raw+cdr", path_note="no C compiler (cc)").slow_path_text().startswith("slower intake")
    ros1 = SourceStatus(path="tcpros", path_note="no C compiler (cc)").slow_path_text()
    assert ros1.startswith("slower intake: the frame loop in C is not used (no C compiler (cc)): Python's decoder")
    assert SourceStatus(path="c+tcpros", path_note="built into a private directory, as X").slow_path_text() == ""
