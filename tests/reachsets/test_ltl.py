"""Past-time LTL monitor: incremental evaluation equals the textbook trace semantics."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from reachsets import ltl
from reachsets.ltl import (
    And,
    Atom,
    Formula,
    Historically,
    LtlMemory,
    Not,
    Once,
    Or,
    Previously,
    Since,
    evaluate_trace,
    step,
)

ATOMS = ("p", "q")


def formulas() -> st.SearchStrategy[Formula]:
    leaves = st.sampled_from([Atom("p"), Atom("q")])

    def extend(children):
        return st.one_of(
            children.map(Not),
            children.map(Previously),
            children.map(Once),
            children.map(Historically),
            st.tuples(children, children).map(lambda ab: Since(*ab)),
            st.tuples(children, children).map(And),
            st.tuples(children, children).map(Or),
        )

    return st.recursive(leaves, extend, max_leaves=6)


traces = st.lists(st.fixed_dictionaries({a: st.booleans() for a in ATOMS}), min_size=1, max_size=8)


@settings(max_examples=150, deadline=None)
@given(formulas(), traces, traces)
def test_incremental_equals_trace_semantics(formula, trace_a, trace_b):
    # two objects with independent traces; object b appears later (first-frame semantics)
    memory: LtlMemory = {}
    trace_b = trace_b[: len(trace_a)]
    offset = len(trace_a) - len(trace_b)
    for t, frame in enumerate(trace_a):
        ids = ["a"]
        atoms = {k: [frame[k]] for k in ATOMS}
        tb = t - offset
        if tb >= 0:
            ids.append("b")
            for k in ATOMS:
                atoms[k].append(trace_b[tb][k])
        values, memory = step(formula, {k: np.array(v) for k, v in atoms.items()}, ids, memory)
        assert bool(values[0]) == evaluate_trace(formula, trace_a, t)
        if tb >= 0:
            assert bool(values[1]) == evaluate_trace(formula, trace_b, tb)


def test_since_holds_until_lhs_breaks():
    f = Since(Atom("p"), Atom("q"))
    rows = [(False, True), (True, False), (True, False), (False, False)]
    memory: LtlMemory = {}
    out = []
    for p, q in rows:
        v, memory = step(f, {"p": np.array([p]), "q": np.array([q])}, ["x"], memory)
        out.append(bool(v[0]))
    assert out == [True, True, True, False]


def test_memory_drops_vanished_objects():
    f = Once(Atom("p"))
    _, memory = step(f, {"p": np.array([True, False])}, ["a", "b"], {})
    _, memory = step(f, {"p": np.array([False])}, ["b"], memory)
    assert all(set(bits) == {"b"} for bits in memory.values())


@settings(max_examples=150, deadline=None)
@given(
    formulas(),
    st.lists(
        st.dictionaries(
            st.sampled_from(["a", "b", "c"]),
            st.fixed_dictionaries({a: st.booleans() for a in ATOMS}),
        ),
        min_size=1,
        max_size=7,
    ),
    st.integers(0, 7),
)
def test_batched_frames_equal_frame_by_frame(formula, frames, split):
    """Objects come and go; a batch of frames (after a split) equals stepping one by one."""
    memory: LtlMemory = {}
    expected = []
    for frame in frames:
        ids = sorted(frame)
        atoms = {k: np.array([frame[i][k] for i in ids], dtype=bool) for k in ATOMS}
        values, memory = step(formula, atoms, ids, memory)
        expected.append(values.tolist())
    split = min(split, len(frames))
    start: LtlMemory = {}
    for frame in frames[:split]:
        ids = sorted(frame)
        atoms = {k: np.array([frame[i][k] for i in ids], dtype=bool) for k in ATOMS}
        _, start = step(formula, atoms, ids, start)
    rest = frames[split:]
    ids = [i for frame in rest for i in sorted(frame)]
    index = np.array([f for f, frame in enumerate(rest) for _ in frame], dtype=np.intp)
    atoms = {k: np.array([fr[i][k] for fr in rest for i in sorted(fr)], bool) for k in ATOMS}
    values, batch_memory = step(formula, atoms, ids, start, frame=index, n_frames=len(rest))
    got = [values[index == f].tolist() for f in range(len(rest))]
    assert got == expected[split:]
    if rest:
        assert batch_memory == memory


@settings(max_examples=150, deadline=None)
@given(
    formulas(),
    st.lists(
        st.tuples(st.sampled_from(["a", "b", "c"]), st.booleans(), st.booleans()),
        min_size=1,
        max_size=6,
    ),
    traces,
)
def test_one_frame_rows_equal_the_chain_scans(formula, rows, history):
    """One frame of a few rows (ids may repeat) in plain Python equals the numpy scans."""
    memory: LtlMemory = {}
    for state in history:  # a memory built over earlier frames of object "a"
        _, memory = step(formula, {k: np.array([v]) for k, v in state.items()}, ["a"], memory)
    ids = [r[0] for r in rows]
    atoms = {"p": np.array([r[1] for r in rows]), "q": np.array([r[2] for r in rows])}
    fast = step(formula, atoms, ids, memory)
    saved = ltl.SCALAR_ROWS_MAX
    ltl.SCALAR_ROWS_MAX = 0
    try:
        scans = step(formula, atoms, ids, memory)
    finally:
        ltl.SCALAR_ROWS_MAX = saved
    assert fast[0].tolist() == scans[0].tolist()
    assert fast[1] == scans[1]
