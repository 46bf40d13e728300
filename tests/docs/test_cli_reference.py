"""The CLI reference is generated from the typer commands and has working examples for each."""

import shlex

import pytest


@pytest.fixture(scope="module")
def command_table(cli_reference):
    return dict(cli_reference.commands()[1])


def test_every_command_has_examples(cli_reference, command_table):
    assert set(cli_reference.EXAMPLES) == set(command_table)
    assert all(cli_reference.EXAMPLES[name] for name in command_table)


def test_examples_use_only_options_the_command_has(cli_reference, command_table):
    for name, examples in cli_reference.EXAMPLES.items():
        options = {opt for param in command_table[name].params for opt in param.opts + param.secondary_opts}
        for line, _ in examples:
            words = shlex.split(line)
            assert words[0] == name
            used = {w for w in words[1:] if w.startswith("-") and not w[1:2].isdigit()}
            assert used <= options | {"--help"}, (line, used - options)


def test_every_command_and_option_is_in_the_reference(cli_reference, command_table):
    text = cli_reference.cli_reference()
    for name, command in command_table.items():
        assert f"kreisel {name}\n" in text
        for param in command.params:
            if param.name != "help":
                assert all(f"``{opt}``" in text for opt in param.opts if opt.startswith("-")), (name, param.name)
