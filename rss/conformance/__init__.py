"""The pinned conformance case format (``conformance/rss-cases-format.md``).

``workbench conformance rss CASES.json`` prints one JSON record per case and sequence step
(:func:`evaluate_document`). The engines never import this package: it builds their inputs
from the case JSON (:mod:`rss.conformance.cases`, :mod:`rss.conformance.unstructured`) and
writes their results as records (:mod:`rss.conformance.records`).
"""

from rss.conformance.cases import CaseDefaults, ParsedCase, parse_case, parse_defaults
from rss.conformance.document import check_expected, evaluate_document, evaluate_formula
from rss.conformance.records import frame_record, json_number, response_record

__all__ = [
    "CaseDefaults",
    "ParsedCase",
    "check_expected",
    "evaluate_document",
    "evaluate_formula",
    "frame_record",
    "json_number",
    "parse_case",
    "parse_defaults",
    "response_record",
]
