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
    assert SourceStatus(path="starting").path_text() == "starting"
