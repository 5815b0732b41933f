"""The LALR(1) driver: runs Lark's parse table over a token list and builds Lark's parse tree.

Lark computes the table (from grammar/glsl.lark, in strict mode, cached on disk) and the
tree-building callbacks (which rule keeps which children, `?rule` inlining, `[x]`
placeholders); this module only runs them, with the table rearranged once per process so
that a step is a dict lookup and an integer test:

* `actions[state][terminal or rule name]` is a new state (shift, or the goto after a
  reduction) when >= 0, and the rule `~action` to reduce by when negative;
* a rule is `(size, name of its left side, callback)`: Lark's own callback, or None when that
  callback would return its one child unchanged (a `?rule` with one alternative symbol, the
  precedence ladder's `?additive_expression: multiplicative_expression`), so those
  reductions only move the state, and a whole run of them (an operand climbing the ladder
  from primary_expression to expression) is one memoised step.

The trees are the ones `Lark.parse` builds, and a missing action raises Lark's
`UnexpectedToken` with the token and the expected terminals, as Lark does
(tests/parse/test_fast_parser.py compares both on the corpus, the lab and mutations).
"""

from __future__ import annotations

from lark import Token, Tree
from lark.exceptions import UnexpectedToken
from lark.grammar import Rule
from lark.parsers.lalr_analysis import Shift

from .lexer import Tokens

END = "$END"


class Driver:
    """Lark's LALR table and callbacks for one start symbol, arranged for `parse`."""

    def __init__(self, parse_table, callbacks, start: str = "start") -> None:
        self.lark_states = parse_table.states
        self.start_state = parse_table.start_states[start]
        self.end_state = parse_table.end_states[start]
        if not all(isinstance(key, Rule) for key in callbacks):
            raise ValueError("terminal callbacks are not supported")
        rules: list[tuple[int, str, object]] = []
        index: dict[int, int] = {}  # id(Rule) -> position in `rules`
        size = max(self.lark_states) + 1
        actions: list[dict[str, int]] = [{} for _ in range(size)]
        for state, row in self.lark_states.items():
            out = actions[state]
            for name, (action, arg) in row.items():
                if action is Shift:
                    out[name] = arg
                    continue
                key = id(arg)
                i = index.get(key)
                if i is None:
                    callback = callbacks[arg]
                    probe = Tree("_probe", [])
                    if len(arg.expansion) == 1 and callback([probe]) is probe:
                        callback = None  # returns its one child: nothing to call
                    i = index[key] = len(rules)
                    rules.append((len(arg.expansion), arg.origin.name, callback))
                out[name] = ~i
        self.actions = actions
        self.rules = rules
        # (state below, state, lookahead) -> the state after the run of one-child reductions
        # that starts there; filled as parses meet them.
        self.chains: dict[tuple[int, int, str], int] = {}

    def _chain(self, below: int, state: int, kind: str) -> int:
        """Run the one-child reductions from `state` on lookahead `kind`: each pops `state` and
        pushes the goto from `below` (the state under it, which stays), so the end state depends
        only on these three."""
        actions = self.actions
        start = state
        while True:
            act = actions[state].get(kind)
            if act is None or act >= 0 or self.rules[~act][2] is not None:
                self.chains[below, start, kind] = state
                return state
            state = actions[below][self.rules[~act][1]]

    def expected(self, state: int) -> set[str]:
        """The terminals the table accepts in `state` (what Lark puts in UnexpectedToken)."""
        return {name for name in self.lark_states[state] if name.isupper()}

    def parse(self, lexed: Tokens):
        """The parse tree of the tokens; raises UnexpectedToken, or the lexer's error when the
        parser gets that far."""
        actions = self.actions
        rules = self.rules
        chains = self.chains
        state = self.start_state
        states = [state]
        values: list = []
        tok = None
        kind = ""
        try:
            for tok in lexed.tokens:
                kind = tok.type
                while True:
                    act = actions[state][kind]
                    if act >= 0:
                        states.append(act)
                        values.append(tok)
                        state = act
                        break
                    size, origin, callback = rules[~act]
                    if callback is None:
                        # The precedence ladder's runs of one-child reductions: one step.
                        below = states[-2]
                        top = chains.get((below, state, kind))
                        if top is None:
                            top = self._chain(below, state, kind)
                        states[-1] = state = top
                        continue
                    if size:
                        children = values[-size:]
                        del values[-size:]
                        del states[-size:]
                        values.append(callback(children))
                    else:
                        values.append(callback([]))
                    state = actions[states[-1]][origin]
                    states.append(state)
        except KeyError:
            if kind in actions[state]:
                raise  # not a missing action: a bug, not a syntax error
            raise UnexpectedToken(tok, self.expected(state)) from None
        if lexed.error is not None:
            raise lexed.error
        end = Token.new_borrow_pos(END, "", tok) if tok is not None else Token(END, "", 0, 1, 1)
        end_state = self.end_state
        row = actions[state]
        while True:
            act = row.get(END)
            if act is None:
                raise UnexpectedToken(end, self.expected(state))
            assert act < 0, "the end of input is never shifted"
            size, origin, callback = rules[~act]
            if callback is None:
                del states[-1]
            elif size:
                children = values[-size:]
                del values[-size:]
                del states[-size:]
                values.append(callback(children))
            else:
                values.append(callback([]))
            state = actions[states[-1]][origin]
            states.append(state)
            if state == end_state:
                return values[-1]
            row = actions[state]
