"""Tiny CommonRoad scenario documents for tests (2018b and 2020a variants).

Network: lanelet 1 (x 0..10, y 0..3) -> lanelet 2 (x 10..20); lanelet 3 on the left of 1,
running the opposite way (its point order goes towards -x).
"""

from __future__ import annotations


def _bound(tag: str, points: list[tuple[float, float]], marking: str | None) -> str:
    pts = "".join(f"<point><x>{x}</x><y>{y}</y></point>" for x, y in points)
    mark = f"<lineMarking>{marking}</lineMarking>" if marking else ""
    return f"<{tag}>{pts}{mark}</{tag}>"


def lanelet(
    lid: int,
    left: list[tuple[float, float]],
    right: list[tuple[float, float]],
    body: str = "",
    *,
    markings: tuple[str | None, str | None] = (None, None),
) -> str:
    return (
        f'<lanelet id="{lid}">{_bound("leftBound", left, markings[0])}'
        f"{_bound('rightBound', right, markings[1])}{body}</lanelet>"
    )


def network(version: str) -> str:
    if version == "2018b":
        speed = "<speedLimit>13.4112</speedLimit>"
        sign = light = inter = ""
        types = ("", "")
    else:
        speed = '<trafficSignRef ref="50"/>'
        sign = (
            '<trafficSign id="50"><trafficSignElement><trafficSignID>R2-1</trafficSignID>'
            "<additionalValue>13.4112</additionalValue></trafficSignElement></trafficSign>"
        )
        light = '<trafficLight id="60"><direction>all</direction></trafficLight>'
        inter = (
            '<intersection id="70"><incoming id="71"><incomingLanelet ref="1"/>'
            '<successorsStraight ref="2"/><successorsLeft ref="99"/></incoming></intersection>'
        )
        types = ("<laneletType>urban</laneletType>", "<laneletType>crosswalk</laneletType>")
    marks = (None, None) if version == "2018b" else ("dashed", "broad_solid")
    one = lanelet(
        1,
        [(0, 3), (10, 3)],
        [(0, 0), (5, 0), (10, 0)],
        '<successor ref="2"/><adjacentLeft ref="3" drivingDir="opposite"/>'
        f'{types[0]}{speed}<trafficLightRef ref="60"/>',
        markings=marks,
    )
    two = lanelet(2, [(10, 3), (20, 3)], [(10, 0), (20, 0)], '<predecessor ref="1"/>')
    three = lanelet(
        3,
        [(10, 3), (0, 3)],
        [(10, 6), (0, 6)],
        f'<adjacentLeft ref="1" drivingDir="opposite"/><successor ref="404"/>{types[1]}',
    )
    return one + two + three + sign + light + inter


def scenario(version: str, body: str, *, dt: str | None = "0.1", net: bool = True) -> bytes:
    step = f' timeStepSize="{dt}"' if dt is not None else ""
    return (
        f'<?xml version="1.0"?><commonRoad commonRoadVersion="{version}" '
        f'benchmarkID="TEST-1"{step}>{network(version) if net else ""}{body}</commonRoad>'
    ).encode()
