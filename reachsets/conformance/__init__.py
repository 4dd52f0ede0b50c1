"""The reach-set case format (``docs/reachset-cases.md``) and a random-case generator.

``workbench conformance reachsets CASES.json`` prints one JSON record per case and sequence
step (:func:`evaluate_document`); :func:`random_document` writes seeded random cases. The
engine never imports this package: it builds engine inputs from the case JSON
(:mod:`reachsets.conformance.cases`) and writes the results as records
(:mod:`reachsets.conformance.records`).
"""

from reachsets.conformance.cases import CaseDefaults, ParsedCase, parse_case, parse_defaults
from reachsets.conformance.document import (
    PreparedDocument,
    evaluate_cases,
    evaluate_document,
    prepare_document,
)
from reachsets.conformance.errors import ReachCaseError
from reachsets.conformance.random_cases import random_document
from reachsets.conformance.records import check_expected, result_record

__all__ = [
    "CaseDefaults",
    "ParsedCase",
    "PreparedDocument",
    "ReachCaseError",
    "check_expected",
    "evaluate_cases",
    "evaluate_document",
    "parse_case",
    "parse_defaults",
    "prepare_document",
    "random_document",
    "result_record",
]
