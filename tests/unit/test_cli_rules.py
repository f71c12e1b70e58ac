"""--query and --rules at start: checked before the app starts; problems exit 2 with the reason."""

import pytest

from console_tui.cli import build_parser, check_rule_arguments, main
from console_tui.model.rules import NodeRule, RuleSet, exclude
from console_tui.model.rules.rulesfile import save_rules


def checked(argv):
    parser = build_parser()
    args = parser.parse_args(argv)
    check_rule_arguments(parser, args)
    return args


def test_valid_query_and_rules_file(tmp_path):
    rules = RuleSet((exclude(NodeRule(("rviz*",))),))
    save_rules(rules, tmp_path / "r.toml")
    args = checked(["--query", "level>=warn -node:x", "--rules", str(tmp_path / "r.toml")])
    assert len(args.query_entries) == 2 and args.rule_set == rules
    args = checked([])
    assert args.query_entries == () and args.rule_set is None


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--query", "level>=warm"], "--query is not valid (at 8):\nlevel>=warm\n       ^ unknown level 'warm'"),
        (["--query", "/a(/"], "missing ), unterminated subpattern"),
        (["--rules", "missing.toml"], "--rules: missing.toml: cannot read"),
    ],
)
def test_bad_query_or_rules_exit_2(argv, message, capsys, tmp_path):
    with pytest.raises(SystemExit) as caught:
        main(argv)
    assert caught.value.code == 2
    assert message in capsys.readouterr().err


def test_malformed_rules_file_exits_2(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text("[[rules]]\nkind = 'severity'\nlevels = ['warm']\n")
    with pytest.raises(SystemExit) as caught:
        main(["--rules", str(bad)])
    assert caught.value.code == 2
    assert "rules[0].levels: unknown level 'warm'" in capsys.readouterr().err
