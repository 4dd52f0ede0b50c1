"""Incidents: runs of unsafe frames per engine, object and cause, with stable ids and severity."""

from workbench.incidents.content import drive_content_hash
from workbench.incidents.detect import IncidentDetector
from workbench.incidents.events import Event, event_id, group_events
from workbench.incidents.facts import FactCollector, register_facts, unregister_facts
from workbench.incidents.find import IncidentReport, IncidentRequest, find_incidents
from workbench.incidents.model import Incident, IncidentSettings, Severity, incident_id
from workbench.incidents.order import severity_key
from workbench.incidents.table import filter_incidents, write_incidents

__all__ = [
    "Event",
    "FactCollector",
    "Incident",
    "IncidentDetector",
    "IncidentReport",
    "IncidentRequest",
    "IncidentSettings",
    "Severity",
    "drive_content_hash",
    "event_id",
    "filter_incidents",
    "find_incidents",
    "group_events",
    "incident_id",
    "register_facts",
    "severity_key",
    "unregister_facts",
    "write_incidents",
]
