"""Incidents: runs of unsafe frames per engine, object and cause, with stable ids and severity."""

from workbench.incidents.content import drive_content_hash
from workbench.incidents.detect import IncidentDetector
from workbench.incidents.facts import FactCollector, register_facts, unregister_facts
from workbench.incidents.find import IncidentReport, IncidentRequest, find_incidents
from workbench.incidents.model import Incident, IncidentSettings, Severity, incident_id
from workbench.incidents.table import filter_incidents, write_incidents

__all__ = [
    "FactCollector",
    "Incident",
    "IncidentDetector",
    "IncidentReport",
    "IncidentRequest",
    "IncidentSettings",
    "Severity",
    "drive_content_hash",
    "filter_incidents",
    "find_incidents",
    "incident_id",
    "register_facts",
    "unregister_facts",
    "write_incidents",
]
