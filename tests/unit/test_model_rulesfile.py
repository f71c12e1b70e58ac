"""Rule sets to and from TOML; malformed files name the problem; config paths."""

from pathlib import Path

import pytest

from console_tui.model.rules import (
    CustomRule,
    LocationRule,
    MessageRule,
    NodeRule,
    RuleSet,
    SeverityRule,
    TimeRangeRule,
    exclude,
    highlight,
)
from console_tui.model.rules.rulesfile import (
    RulesFileError,
    config_dir,
    dumps_rules,
    last_rules_path,
    load_rules,
    loads_rules,
    query_history_path,
    save_rules,
    state_dir,
)

EVERY_KIND = RuleSet(
    (
        exclude(MessageRule('a "quoted"\\ \t\n\x01 ✓ text', ignore_case=True)),
        exclude(MessageRule(r"^time(out|d out)\d+$", regex=True), enabled=False),
        highlight(SeverityRule.of("warn", "fatal"), inverted=True),
        highlight(NodeRule(("nav*", "/ns/x", "ロボット"))),
        exclude(LocationRule(file="planner.cpp", function="^on_", line=7, regex=True)),
        exclude(LocationRule(function="spin")),
        highlight(TimeRangeRule(1_714_564_800_123_456_789, None)),
        highlight(TimeRangeRule(None, -5)),
        exclude(CustomRule((SeverityRule.of("debug"), NodeRule(("rviz*",)), MessageRule("")))),
        exclude(MessageRule("")),
    ),
    highlighted_only=True,
)


def test_round_trip_every_kind(tmp_path):
    path = tmp_path / "deep" / "rules.toml"
    save_rules(EVERY_KIND, path)
    assert load_rules(path) == EVERY_KIND
    assert loads_rules(dumps_rules(RuleSet())) == RuleSet()


def test_written_file_is_readable_by_people():
    text = dumps_rules(EVERY_KIND)
    assert 'role = "highlight"' in text and 'levels = ["warn", "fatal"]' in text
    assert "[[rules.parts]]" in text and "# 2024-05-01 12:00:00.123456789 +0000" in text


@pytest.mark.parametrize(
    ("text", "problem"),
    [
        ("rules = [", "not valid TOML"),
        ("[[rules]]\nkind = 'message'\ntext = 'x'\nbogus\nx = 1", "line 4"),
        ("colour = 1", "unknown key 'colour'"),
        ("highlighted_only = 'yes'", "highlighted_only: expected true or false"),
        ("rules = 3", "rules: expected an array of tables"),
        (
            "[[rules]]\nkind = 'nodes'",
            "rules[0].kind: expected one of custom, location, message, node, robot, severity, time",
        ),
        (
            "[[rules]]\nkind = 'node'\n[[rules]]\nkind = 'node'\nnames = 'a'\nrole = 'hide'",
            "rules[1].role: expected 'exclude' or 'highlight'",
        ),
        ("[[rules]]\nkind = 'node'\nenabled = 1", "rules[0].enabled: expected true or false"),
        ("[[rules]]\nkind = 'severity'\nlevels = ['warm']", "rules[0].levels: unknown level 'warm'"),
        ("[[rules]]\nkind = 'severity'\nlevels = 3", "rules[0].levels: expected a list of text"),
        ("[[rules]]\nkind = 'message'\ntext = 'a('\nregex = true", "rules[0]: invalid regular expression 'a('"),
        ("[[rules]]\nkind = 'message'\ntxt = 'a'", "rules[0].txt: not a field of a message rule"),
        ("[[rules]]\nkind = 'location'\nline = 'x'", "rules[0].line: expected a whole number"),
        ("[[rules]]\nkind = 'location'\nline = -1", "rules[0].line: not a line number: -1"),
        ("[[rules]]\nkind = 'time'\nstart_ns = 5\nend_ns = 1", "rules[0]: time range: the start is after the end"),
        ("[[rules]]\nkind = 'custom'\n[[rules.parts]]\nkind = 'x'", "rules[0].parts[0].kind: expected one of"),
        ("[[rules]]\nkind = 'custom'\nparts = 1", "rules[0].parts: expected a list of rules"),
    ],
)
def test_malformed_files_name_the_problem(tmp_path, text, problem):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(RulesFileError) as caught:
        load_rules(path)
    assert str(caught.value).startswith(f"{path}: ")
    assert problem in str(caught.value)


def test_unreadable_files(tmp_path):
    with pytest.raises(RulesFileError, match="cannot read"):
        load_rules(tmp_path / "missing.toml")
    (tmp_path / "binary.toml").write_bytes(b"\xff\xfe\x00")
    with pytest.raises(RulesFileError, match="cannot read"):
        load_rules(tmp_path / "binary.toml")


def test_config_paths_follow_xdg(monkeypatch, tmp_path):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path))
    assert config_dir() == tmp_path / "console-tui"
    for unset in ("", "relative/dir"):
        monkeypatch.setenv("XDG_CONFIG_HOME", unset)
        assert config_dir() == Path.home() / ".config" / "console-tui"


def test_state_paths_follow_xdg_state_home(monkeypatch, tmp_path):
    monkeypatch.setenv("XDG_STATE_HOME", str(tmp_path / "state"))
    assert state_dir() == tmp_path / "state" / "console-tui"
    assert last_rules_path() == state_dir() / "last-rules.toml"
    assert query_history_path() == state_dir() / "query-history.txt"
    for unset in ("", "relative/dir"):
        monkeypatch.setenv("XDG_STATE_HOME", unset)
        assert state_dir() == Path.home() / ".local" / "state" / "console-tui"


def test_an_older_versions_files_move_from_the_config_folder_once(monkeypatch, tmp_path):
    monkeypatch.setenv("XDG_STATE_HOME", str(tmp_path / "state"))
    old = config_dir()
    old.mkdir(parents=True)
    (old / "last-rules.toml").write_text(dumps_rules(EVERY_KIND))
    (old / "query-history.txt").write_text("level>=warn\n")
    assert load_rules(last_rules_path()) == EVERY_KIND
    assert query_history_path().read_text() == "level>=warn\n"
    assert not (old / "last-rules.toml").exists() and not (old / "query-history.txt").exists()
    # Once there, the state directory's file is the one: a later file in the old place stays put.
    (old / "last-rules.toml").write_text("stale")
    assert last_rules_path().read_text() != "stale" and (old / "last-rules.toml").read_text() == "stale"


def test_what_is_not_a_plain_file_of_ours_is_not_moved(monkeypatch, tmp_path):
    monkeypatch.setenv("XDG_STATE_HOME", str(tmp_path / "state"))
    old = config_dir()
    old.mkdir(parents=True)
    (tmp_path / "elsewhere.toml").write_text("x")
    (old / "last-rules.toml").symlink_to(tmp_path / "elsewhere.toml")
    assert last_rules_path() == state_dir() / "last-rules.toml" and not last_rules_path().exists()
    assert (old / "last-rules.toml").is_symlink() and (tmp_path / "elsewhere.toml").read_text() == "x"
