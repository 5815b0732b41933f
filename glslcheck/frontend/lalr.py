"""The LALR(1) driver: runs Lark's parse table over a token list and builds Lark's parse tree.

Lark computes the table (from grammar/glsl.lark, in strict mode) and the tree-building
callbacks (which rule keeps which children, `?rule` inlining, `[x]` placeholders) ahead of
time; `tables_from_lark` writes them down as data (frontend/parse_tables.py ships it, so Lark is not
imported at run time) and this module runs them, the table arranged so that a step is a dict
lookup and an integer test:

* `actions[state][terminal or rule name]` is a new state (shift, or the goto after a
  reduction) when >= 0, and the rule `~action` to reduce by when negative;
* a rule is `(size, name of its left side, callback)`: a function that does what Lark's own
  callback does (read from it, `_tree_shape`), or None when that callback would return its
  one child unchanged (a `?rule` with one alternative symbol, the
  precedence ladder's `?additive_expression: multiplicative_expression`), so those
  reductions only move the state, and a whole run of them (an operand climbing the ladder
  from primary_expression to expression) is one memoised step.

The trees are the ones `Lark.parse` builds (this module's `Tree` and frontend/lexer.py's `Token`
have Lark's attributes), and a missing action raises `UnexpectedToken` with the token and the
expected terminals, as Lark does
(tests/parse/test_fast_parser.py compares both on the corpus, the lab and mutations).
"""

from __future__ import annotations

from itertools import chain

from .lexer import Token, Tokens, UnexpectedInput

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Callable
    from typing import Any

END = "$END"


class Tree:
    """A node of the parse tree: its rule (or alias) name and its children (trees, tokens, and
    None for an absent `[optional]` part), as Lark's Tree has them; and, as a token has them,
    `start_pos` and `end_pos`: where its first token starts and its last token ends in the
    text (None for a tree without tokens). `Driver.parse` sets them as it reduces, from the
    children it reduces (a tree's tokens are exactly those: the tables keep every token)."""

    __slots__ = ("data", "children", "start_pos", "end_pos")

    def __init__(
        self, data: str, children: list, start_pos: int | None = None, end_pos: int | None = None
    ) -> None:
        self.data = data
        self.children = children
        self.start_pos = start_pos
        self.end_pos = end_pos

    def __repr__(self) -> str:
        return f"Tree({self.data!r}, {self.children!r})"

    def iter_subtrees(self):
        """This tree and every tree under it."""
        stack = [self]
        while stack:
            tree = stack.pop()
            yield tree
            stack.extend(c for c in tree.children if isinstance(c, Tree))


class UnexpectedToken(UnexpectedInput):
    """No action for `token` in the parser's state; `expected` are the terminals it accepts
    there."""

    def __init__(self, token: Token, expected: set[str]) -> None:
        super().__init__(
            f"unexpected {token.type} {token.value!r}, expected one of {sorted(expected)}"
        )
        self.token = token
        self.expected = expected


def tables_from_lark(lalr) -> dict:
    """The driver's tables from Lark's LALR parser (`lark.parser.parser.parser`), as JSON-ready
    data: each rule's tree shape is read from the callback Lark built for it, so the trees are
    Lark's (frontend/parse_tables.py builds them ahead of time; `Driver` runs them)."""
    from lark.parsers.lalr_analysis import Shift

    parse_table = lalr.parse_table
    states = parse_table.states
    start = parse_table.start_states["start"]
    # Lark numbers its states in an order that changes with Python's string hashing: number
    # them breadth-first from the start state instead, and the rules as they are first met,
    # so the same grammar always gives the same tables.
    order = [start]
    number = {start: 0}
    for state in order:
        for name in sorted(states[state]):
            action, arg = states[state][name]
            if action is Shift and arg not in number:
                number[arg] = len(order)
                order.append(arg)
    if len(order) != len(states):
        raise ValueError("the LALR table has states the start state does not reach")
    rules: list[list] = []
    index: dict[int, int] = {}  # id(Rule) -> position in `rules`
    actions: list[dict[str, int]] = []
    for state in order:
        out: dict[str, int] = {}
        for name in sorted(states[state]):
            action, arg = states[state][name]
            if action is Shift:
                out[name] = number[arg]
                continue
            i = index.get(id(arg))
            if i is None:
                i = index[id(arg)] = len(rules)
                rules.append(
                    [len(arg.expansion), arg.origin.name, *_tree_shape(lalr.callbacks[arg])]
                )
            out[name] = ~i
        actions.append(out)
    return {
        "start": 0,
        "end": number[parse_table.end_states["start"]],
        "actions": actions,
        "rules": rules,
    }


def _tree_shape(callback) -> list:
    """[tree name, expand a single child, kept children or None, Nones to append] of one of
    Lark's rule callbacks (lark/parse_tree_builder.py: a child filter around ExpandSingleChild
    around `partial(Tree, name)`); kept children are [index, inline its children, Nones before]."""
    from functools import partial

    from lark.parse_tree_builder import (
        ChildFilterLALR,
        ChildFilterLALR_NoPlaceholders,
        ExpandSingleChild,
    )

    keep = None
    append_none = 0
    if isinstance(callback, ChildFilterLALR):
        keep = [list(x) for x in callback.to_include]
        append_none = callback.append_none
        callback = callback.node_builder
    elif isinstance(callback, ChildFilterLALR_NoPlaceholders):
        keep = [[i, expand, 0] for i, expand in callback.to_include]
        callback = callback.node_builder
    expand1 = isinstance(callback, ExpandSingleChild)
    if expand1:
        callback = callback.node_builder
    if not (isinstance(callback, partial) and len(callback.args) == 1 and not callback.keywords):
        raise ValueError(f"a rule callback of an unknown shape: {callback!r}")
    return [str(callback.args[0]), expand1, keep, append_none]


def _callback(
    size: int, name: str, expand1: bool, keep: list | None, append_none: int
) -> Callable[[list], Any] | None:
    """The function that builds a rule's tree from its `size` children, as Lark's callback
    does; None when it would return its one child unchanged (nothing to call)."""
    keep = None if keep is None else [tuple(k) for k in keep]  # lists built, tuples shipped
    if size == 1 and expand1 and (keep is None or (keep == [(0, False, 0)] and not append_none)):
        return None
    if keep is None:
        if expand1:
            return lambda children: children[0] if len(children) == 1 else Tree(name, children)
        return lambda children: Tree(name, children)

    def build(children):
        filtered = []
        for i, expand, add_none in keep:
            if add_none:
                filtered += [None] * add_none
            if expand:
                if filtered:
                    filtered += children[i].children
                else:  # left recursion: reuse the list (each tree is used once)
                    filtered = children[i].children
            else:
                filtered.append(children[i])
        if append_none:
            filtered += [None] * append_none
        if expand1 and len(filtered) == 1:
            return filtered[0]
        return Tree(name, filtered)

    return build


class Driver:
    """The LALR tables of one grammar (`tables_from_lark`), arranged for `parse`."""

    def __init__(self, tables: dict) -> None:
        self.start_state: int = tables["start"]
        self.end_state: int = tables["end"]
        self.actions: list[dict[str, int]] = tables["actions"]
        # (size, origin, callback, plain): `plain` is the tree's name when the callback would
        # only make `Tree(name, children)`, which the parse loop then makes itself (most
        # reductions are of this kind, and a Python class call for each is dear)
        self.rules: list[tuple[int, str, Callable[[list], Any] | None, str | None]] = [
            (
                size,
                origin,
                _callback(size, *shape),
                shape[0] if shape[2] is None and not shape[1] else None,
            )
            for size, origin, *shape in tables["rules"]
        ]
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
        return {name for name in self.actions[state] if name.isupper()}

    def parse(self, lexed: Tokens):
        """The parse tree of the tokens; raises UnexpectedToken, or the lexer's error when the
        parser gets that far."""
        actions = self.actions
        rules = self.rules
        chains = self.chains
        new_tree = object.__new__
        state = self.start_state
        states = [state]
        values: list = []
        tok = None
        kind = ""
        try:
            # one loop for the tokens and the end of input: the end state has no action, so the
            # END lookahead's KeyError there is the accept (no test per step)
            for tok in chain(lexed.tokens, _end_of_input(lexed)):
                kind = tok.type
                while True:
                    act = actions[state][kind]
                    if act >= 0:
                        states.append(act)
                        values.append(tok)
                        state = act
                        break
                    size, origin, callback, plain = rules[~act]
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
                        if plain is not None:
                            value = new_tree(Tree)
                            value.data = plain
                            value.children = children
                        else:
                            value = callback(children)
                        if type(value) is Tree:
                            # The tree's span, bottom-up: from its first token to its last
                            # (children without tokens, empty trees, have None).
                            start = children[0].start_pos
                            if start is None:
                                start = next(
                                    (c.start_pos for c in children if c.start_pos is not None), None
                                )
                            end = children[-1].end_pos
                            if end is None:
                                end = next(
                                    (
                                        c.end_pos
                                        for c in reversed(children)
                                        if c.end_pos is not None
                                    ),
                                    None,
                                )
                            value.start_pos = start
                            value.end_pos = end
                        values.append(value)
                    else:
                        values.append(callback([]))
                    state = actions[states[-1]][origin]
                    states.append(state)
        except KeyError:
            if state == self.end_state and kind == END:
                return values[-1]
            if kind in actions[state]:
                raise  # not a missing action: a bug, not a syntax error
            assert tok is not None  # the loop met a token: at least the end of input
            raise UnexpectedToken(tok, self.expected(state)) from None
        raise AssertionError("the end of input is never shifted")


def _end_of_input(lexed: Tokens):
    """The END token after the last token (at its position), once the parser got there: the
    lexer's error first, if it stopped early."""
    if lexed.error is not None:
        raise lexed.error
    last = lexed.tokens[-1] if lexed.tokens else None
    yield Token.new_borrow_pos(END, "", last) if last is not None else Token(END, "", 0, 1, 1)
