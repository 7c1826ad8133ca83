"""Examples of the contract: a request for each endpoint, and the service's answer to it.

Each answer is the service's own to its request, with every ``segments`` list cut to its
first :data:`SHOWN_SEGMENTS` (:func:`shorten`) so that the document stays readable (the
statistics are those of the whole answer). They were made once by posting the requests to
the service and pasted here; ``tests/api/test_examples.py`` checks that each is still what
the service answers, and valid against its response model.
"""

from __future__ import annotations

from typing import Any

from .drawing_schemas import DRAWING_EXAMPLE
from .path_schemas import PATH_EXAMPLE
from .schemas import PAPER_EXAMPLE

#: Segments shown of each arc spline in an example answer.
SHOWN_SEGMENTS = 2


def shorten(answer: Any, keep: int = SHOWN_SEGMENTS) -> Any:
    """``answer`` with every ``segments`` list cut to its first ``keep`` segments."""
    if isinstance(answer, dict):
        return {
            key: value[:keep] if key == "segments" else shorten(value, keep)
            for key, value in answer.items()
        }
    if isinstance(answer, list):
        return [shorten(value, keep) for value in answer]
    return answer


# -- requests ----------------------------------------------------------------------------

SPIRAL_PROGRAM_REQUEST: dict[str, Any] = {
    **PAPER_EXAMPLE,
    "gcode": {"feed_rate": 1200},
    "output": "gcode",
}
#: Valid by the schema, but its control points are not of the paper's form (B2 − B1 ≠ B1 − B0).
SPIRAL_NOT_OF_THE_FORM: dict[str, Any] = {
    "spiral": {"control_points": [[0, 0], [1, 0], [3, 0], [4, 1]]},
    "tolerance": 0.001,
}
PATH_PROGRAM_REQUEST: dict[str, Any] = {
    **PATH_EXAMPLE,
    "gcode": {"feed_rate": 600},
    "output": "gcode",
}
#: Valid by the schema, but the path data ends where a coordinate is expected.
PATH_CUT_SHORT: dict[str, Any] = {"path": "M 0 0 L 10", "tolerance": 0.01}
DRAWING_PROGRAM_REQUEST: dict[str, Any] = {
    **DRAWING_EXAMPLE,
    "gcode": {"feed_rate": 600, "safe_z": 5, "cut_z": -1},
    "output": "gcode",
}
DRAWING_OFFSET_REQUEST: dict[str, Any] = {
    **DRAWING_EXAMPLE,
    "offset": {"distance": 1.5, "side": "outside"},
}

# -- answers (the service's, see the module docstring) -------------------------------------

_NOT_OF_THE_FORM = (
    "B2 − B1 must equal B1 − B0 (the paper's form); they differ by 1 of |B1 − B0| (allowed 1e-06)"
)
_CUT_SHORT = "at character 10: expected a number for command 'L', found end of data"

SPIRAL_ANSWER: dict[str, Any] = {
    "segments": [
        {
            "type": "arc",
            "start": [1.5, 3.0],
            "end": [2.0758631162109973, 3.0009409020612656],
            "center": [1.5, 179.22408726730004],
            "radius": 176.22408726730004,
            "direction": "ccw",
            "start_angle_rad": -1.5707963267948966,
            "sweep_rad": 0.003267794715426587,
            "length": 0.5758641411029567,
            "u_start": 0.0,
            "u_end": 0.08626006554284545,
            "max_deviation": 0.00017668407143971442,
            "u_at_max_deviation": 0.06461062256820577,
        },
        {
            "type": "arc",
            "start": [2.0758631162109973, 3.0009409020612656],
            "end": [2.3612452585516435, 3.002814382722367],
            "center": [1.9344297488482494, 46.281769793630616],
            "radius": 43.28105997938022,
            "direction": "ccw",
            "start_angle_rad": -1.56752853207947,
            "sweep_rad": 0.006593849802934968,
            "length": 0.28538880881585277,
            "u_start": 0.08626006554284545,
            "u_end": 0.1292204280524405,
            "max_deviation": 0.00010372235149203152,
            "u_at_max_deviation": 0.08626006554284545,
        },
    ],
    "stats": {
        "arc_count": 12,
        "line_count": 0,
        "segment_count": 12,
        "max_deviation": 0.0009588455798196795,
        "deviation_ratio": 0.9588455798196795,
        "mean_segment_deviation": 0.0002970886346979173,
        "spline_length": 5.83394795298412,
        "min_radius": 2.4058748656984985,
        "max_radius": 176.22408726730004,
        "tolerance": 0.001,
        "strategy": "subdivide",
        "u_at_max_deviation": 0.3608008332681409,
        "spiral_length": 5.834027937757817,
    },
    "gcode": None,
}
SPIRAL_PROGRAM = """\
G17 G21 G90 G91.1 G94 F1200
G0 X1.5000 Y3.0000
G3 X2.0759 Y3.0009 I0.0125 J176.2241
G3 X2.3612 Y3.0028 I-0.1456 J43.2809
G3 X2.8367 Y3.0107 I-0.3508 J35.4313
G3 X3.2070 Y3.0225 I-0.4999 J21.5031
G3 X4.1261 Y3.0867 I-0.6405 J15.7815
G3 X4.7861 Y3.1791 I-0.8144 J8.2206
G3 X5.4053 Y3.3234 I-1.1506 J6.3380
G3 X5.8867 Y3.4936 I-1.1418 J3.9956
G3 X6.1569 Y3.6217 I-1.4060 J3.3146
G3 X6.3921 Y3.7594 I-1.3931 J2.6491
G3 X6.7272 Y4.0158 I-1.4788 J2.2799
G3 X7.0000 Y4.3043 I-1.6058 J1.7916
M2
"""
SPIRAL_NOT_OF_THE_FORM_PROBLEM: dict[str, Any] = {
    "type": "urn:arcspline:problem:invalid-input",
    "title": "Invalid curve",
    "status": 422,
    "detail": f"body.jobs.1.spiral.control_points: {_NOT_OF_THE_FORM}",
    "request_id": "5f0c6e1e2d7b4c0e9a3b1d2c4e6f8a90",
    "errors": [
        {
            "loc": ["body", "jobs", 1, "spiral", "control_points"],
            "msg": _NOT_OF_THE_FORM,
            "type": "invalid_input",
        }
    ],
}
PATH_ANSWER: dict[str, Any] = {
    "subpaths": [
        {
            "closed": True,
            "segments": [
                {
                    "type": "arc",
                    "start": [0.0, 0.0],
                    "end": [5.68421805376046, 1.077398800213573],
                    "center": [0.0, 15.533302548120066],
                    "radius": 15.533302548120066,
                    "direction": "ccw",
                    "start_angle_rad": -1.5707963267948966,
                    "sweep_rad": 0.3746399862528929,
                    "length": 5.819396253089728,
                    "u_start": 0.0,
                    "u_end": 0.18947835700434537,
                    "max_deviation": 0.009157597637222126,
                    "u_at_max_deviation": 0.1333294851261423,
                    "source_segment": 0,
                },
                {
                    "type": "arc",
                    "start": [5.68421805376046, 1.077398800213573],
                    "end": [9.891400723449758, 3.2613269423954128],
                    "center": [-2.6570903300981827, 22.290721369514756],
                    "radius": 22.794351931648624,
                    "direction": "ccw",
                    "start_angle_rad": -1.1961563405420037,
                    "sweep_rad": 0.2083335806404622,
                    "length": 4.748828956299194,
                    "u_start": 0.18947835700434537,
                    "u_end": 0.32971335744832525,
                    "max_deviation": 0.008913665172868084,
                    "u_at_max_deviation": 0.2370025902875235,
                    "source_segment": 0,
                },
            ],
            "stats": {
                "arc_count": 8,
                "line_count": 2,
                "segment_count": 10,
                "max_deviation": 0.009157597637222126,
                "deviation_ratio": 0.9157597637222126,
                "mean_segment_deviation": 0.0046887729432926895,
                "spline_length": 128.3864812720072,
                "min_radius": 5.0,
                "max_radius": 149.14545186754043,
                "tolerance": 0.01,
                "strategy": "fewest-arcs",
                "max_deviation_segment": 0,
                "t_at_max_deviation": 0.1333294851261423,
                "curve_length": 128.38576794273988,
            },
        }
    ],
    "stats": {
        "arc_count": 8,
        "line_count": 2,
        "segment_count": 10,
        "max_deviation": 0.009157597637222126,
        "deviation_ratio": 0.9157597637222126,
        "mean_segment_deviation": 0.0046887729432926895,
        "spline_length": 128.3864812720072,
        "min_radius": 5.0,
        "max_radius": 149.14545186754043,
        "tolerance": 0.01,
        "strategy": "fewest-arcs",
        "max_deviation_subpath": 0,
        "max_deviation_segment": 0,
        "t_at_max_deviation": 0.1333294851261423,
        "curve_length": 128.38576794273988,
        "subpath_count": 1,
    },
    "gcode": None,
}
PATH_PROGRAM = """\
G17 G21 G90 G91.1 G94 F600
G0 X0.0000 Y0.0000
G3 X5.6842 Y1.0774 I0.0000 J15.5333
G3 X9.8914 Y3.2613 I-8.3412 J21.2134
G3 X13.9378 Y6.4742 I-16.1622 J24.5095
G3 X18.4070 Y11.2940 I-35.4155 J37.3213
G3 X21.4212 Y15.2956 I-50.8498 J41.4385
G3 X25.9749 Y22.4936 I-80.7814 J56.1444
G3 X30.0000 Y30.0000 I-129.3748 J74.2061
G1 X40.0000 Y30.0000
G3 X50.0000 Y30.0000 I5.0000 J0.0000
G1 X0.0000 Y0.0000
M2
"""
PATH_CUT_SHORT_PROBLEM: dict[str, Any] = {
    "type": "urn:arcspline:problem:invalid-input",
    "title": "Invalid curve",
    "status": 422,
    "detail": f"body.jobs.1.path: {_CUT_SHORT}",
    "request_id": "0b7e2c4d6f8a4b1c9d3e5f7a2c4e6b8d",
    "errors": [
        {
            "loc": ["body", "jobs", 1, "path"],
            "msg": _CUT_SHORT,
            "type": "invalid_input",
        }
    ],
}
DRAWING_ANSWER: dict[str, Any] = {
    "toolpaths": [
        {
            "closed": True,
            "segments": [
                {
                    "type": "arc",
                    "start": [5.0, 5.0],
                    "end": [8.356311928130932, 12.736053267842381],
                    "center": [50.72327330072302, -10.241091100241007],
                    "radius": 48.19656190288324,
                    "direction": "cw",
                    "start_angle_rad": 2.819842099193151,
                    "sweep_rad": -0.1751898438421859,
                    "length": 8.44354815349636,
                    "u_start": 0.0,
                    "u_end": 0.09497698480281441,
                    "max_deviation": 0.00997237617564848,
                    "u_at_max_deviation": 0.06261451885458047,
                    "source_segment": 0,
                },
                {
                    "type": "arc",
                    "start": [8.356311928130932, 12.736053267842381],
                    "end": [12.426573873937109, 18.659412901169464],
                    "center": [38.46397544741846, -3.5924279084327875],
                    "radius": 34.25041167803111,
                    "direction": "cw",
                    "start_angle_rad": 2.644652255350965,
                    "sweep_rad": -0.2102243060673617,
                    "length": 7.20026902753555,
                    "u_start": 0.09497698480281441,
                    "u_end": 0.18658534567994184,
                    "max_deviation": 0.008907510778942508,
                    "u_at_max_deviation": 0.12482601749939912,
                    "source_segment": 0,
                },
            ],
            "stats": {
                "arc_count": 10,
                "line_count": 1,
                "segment_count": 11,
                "max_deviation": 0.00997237617564848,
                "deviation_ratio": 0.997237617564848,
                "mean_segment_deviation": 0.006573144103216439,
                "spline_length": 121.90795743542098,
                "min_radius": 20.294562324022827,
                "max_radius": 50.21465560318106,
                "tolerance": 0.01,
                "strategy": "fewest-arcs",
                "max_deviation_segment": 0,
                "t_at_max_deviation": 0.06261451885458047,
                "curve_length": 121.9062525230061,
            },
            "sources": ["path (line 1)"],
        },
        {
            "closed": True,
            "segments": [
                {
                    "type": "arc",
                    "start": [36.0, 15.0],
                    "end": [24.0, 15.0],
                    "center": [30.0, 15.0],
                    "radius": 6.0,
                    "direction": "cw",
                    "start_angle_rad": 0.0,
                    "sweep_rad": -3.141592653589793,
                    "length": 18.84955592153876,
                    "u_start": 0.0,
                    "u_end": 1.0,
                    "max_deviation": 0.0,
                    "u_at_max_deviation": 0.0,
                    "source_segment": 0,
                },
                {
                    "type": "arc",
                    "start": [24.0, 15.0],
                    "end": [36.0, 15.0],
                    "center": [30.0, 15.0],
                    "radius": 6.0,
                    "direction": "cw",
                    "start_angle_rad": 3.141592653589793,
                    "sweep_rad": -3.141592653589793,
                    "length": 18.84955592153876,
                    "u_start": 0.0,
                    "u_end": 1.0,
                    "max_deviation": 0.0,
                    "u_at_max_deviation": 0.0,
                    "source_segment": 1,
                },
            ],
            "stats": {
                "arc_count": 2,
                "line_count": 0,
                "segment_count": 2,
                "max_deviation": 0.0,
                "deviation_ratio": 0.0,
                "mean_segment_deviation": 0.0,
                "spline_length": 37.69911184307752,
                "min_radius": 6.0,
                "max_radius": 6.0,
                "tolerance": 0.01,
                "strategy": "fewest-arcs",
                "max_deviation_segment": 0,
                "t_at_max_deviation": 0.0,
                "curve_length": 37.69911184307751,
            },
            "sources": ["circle (line 1)"],
        },
    ],
    "stats": {
        "arc_count": 12,
        "line_count": 1,
        "segment_count": 13,
        "max_deviation": 0.00997237617564848,
        "deviation_ratio": 0.997237617564848,
        "mean_segment_deviation": 0.005561891164260064,
        "spline_length": 159.60706927849847,
        "min_radius": 6.0,
        "max_radius": 50.21465560318106,
        "tolerance": 0.01,
        "strategy": "fewest-arcs",
        "max_deviation_segment": 0,
        "t_at_max_deviation": 0.06261451885458047,
        "curve_length": 159.60536436608362,
        "toolpath_count": 2,
        "max_deviation_toolpath": 0,
    },
    "units": "mm",
    "document": {
        "units": "mm",
        "elements_in": 2,
        "elements_read": 2,
        "elements_skipped": 0,
        "warnings": [],
    },
    "budget": {
        "tolerance": 0.01,
        "curve_approximation": 0.0,
        "snap_move": 0.0,
        "join_gap": 0.0,
        "fit": 0.01,
    },
    "join": {"tolerance": 0.001, "joins": 0},
    "rapids": {"before": 39.644062761670135, "after": 39.644062761670135},
    "gcode": None,
}
DRAWING_PROGRAM = """\
G17 G21 G90 G91.1 G94 F600
G0 Z5.0000
G0 X5.0000 Y5.0000
G1 Z-1.0000
G2 X8.3563 Y12.7361 I45.7233 J-15.2409
G2 X12.4266 Y18.6594 I30.1075 J-16.3287
G2 X16.5834 Y22.6589 I22.5189 J-19.2447
G2 X22.8833 Y26.2113 I14.5062 J-18.3633
G2 X30.0000 Y27.5000 I7.1167 J-19.0059
G2 X38.6131 Y25.5905 I0.0000 J-20.3799
G2 X44.2357 Y21.9936 I-10.6546 J-22.8481
G2 X48.8661 Y17.0451 I-18.7890 J-22.2219
G2 X53.2873 Y9.4284 I-32.4045 J-23.9010
G2 X55.0000 Y5.0000 I-45.9253 J-20.3072
G1 X5.0000 Y5.0000
G0 Z5.0000
G0 X36.0000 Y15.0000
G1 Z-1.0000
G2 X24.0000 Y15.0000 I-6.0000 J0.0000
G2 X36.0000 Y15.0000 I6.0000 J0.0000
G0 Z5.0000
M2
"""
READY_ANSWER: dict[str, Any] = {
    "status": "ready",
    "workers": 2,
    "in_flight": 0,
    "queue_capacity": 64,
}
DRAWING_OFFSET_ANSWER: dict[str, Any] = {
    "toolpaths": [
        {
            "closed": True,
            "segments": [
                {
                    "type": "arc",
                    "start": [3.576975052924233, 5.474341649025259],
                    "end": [7.037743973285046, 13.45116063632178],
                    "center": [50.72327330072302, -10.241091100241007],
                    "radius": 49.69656190288324,
                    "direction": "cw",
                    "start_angle_rad": 2.819842099193151,
                    "sweep_rad": -0.1751898438421859,
                    "length": 8.706332919259639,
                    "u_start": 0.0,
                    "u_end": 1.0,
                    "max_deviation": 0.0,
                    "u_at_max_deviation": 0.0,
                    "source_segment": 0,
                },
                {
                    "type": "arc",
                    "start": [7.037743973285046, 13.45116063632178],
                    "end": [11.286263423733882, 19.633934361762982],
                    "center": [38.46397544741846, -3.5924279084327875],
                    "radius": 35.75041167803111,
                    "direction": "cw",
                    "start_angle_rad": 2.644652255350965,
                    "sweep_rad": -0.2102243060673617,
                    "length": 7.515605486636593,
                    "u_start": 0.0,
                    "u_end": 1.0,
                    "max_deviation": 0.0,
                    "u_at_max_deviation": 0.0,
                    "source_segment": 1,
                },
            ],
            "stats": {
                "arc_count": 12,
                "line_count": 1,
                "segment_count": 13,
                "max_deviation": 0.0,
                "deviation_ratio": 0.0,
                "mean_segment_deviation": 0.0,
                "spline_length": 131.33273539619037,
                "min_radius": 1.5,
                "max_radius": 51.71465560318106,
                "tolerance": 0.01,
                "strategy": "fewest-arcs",
                "max_deviation_segment": 0,
                "t_at_max_deviation": 0.0,
                "curve_length": 131.3327353961904,
            },
            "sources": ["path (line 1)"],
        },
        {
            "closed": True,
            "segments": [
                {
                    "type": "arc",
                    "start": [37.5, 15.0],
                    "end": [22.5, 14.999999999999998],
                    "center": [30.0, 15.0],
                    "radius": 7.5,
                    "direction": "cw",
                    "start_angle_rad": 0.0,
                    "sweep_rad": -3.141592653589793,
                    "length": 23.561944901923447,
                    "u_start": 0.0,
                    "u_end": 1.0,
                    "max_deviation": 0.0,
                    "u_at_max_deviation": 0.0,
                    "source_segment": 0,
                },
                {
                    "type": "arc",
                    "start": [22.5, 14.999999999999998],
                    "end": [37.5, 15.0],
                    "center": [30.0, 15.0],
                    "radius": 7.5,
                    "direction": "cw",
                    "start_angle_rad": -3.141592653589793,
                    "sweep_rad": -3.141592653589793,
                    "length": 23.561944901923447,
                    "u_start": 0.0,
                    "u_end": 1.0,
                    "max_deviation": 0.0,
                    "u_at_max_deviation": 0.0,
                    "source_segment": 1,
                },
            ],
            "stats": {
                "arc_count": 2,
                "line_count": 0,
                "segment_count": 2,
                "max_deviation": 0.0,
                "deviation_ratio": 0.0,
                "mean_segment_deviation": 0.0,
                "spline_length": 47.12388980384689,
                "min_radius": 7.5,
                "max_radius": 7.5,
                "tolerance": 0.01,
                "strategy": "fewest-arcs",
                "max_deviation_segment": 0,
                "t_at_max_deviation": 0.0,
                "curve_length": 47.123889803846886,
            },
            "sources": ["circle (line 1)"],
        },
    ],
    "stats": {
        "arc_count": 14,
        "line_count": 1,
        "segment_count": 15,
        "max_deviation": 0.0,
        "deviation_ratio": 0.0,
        "mean_segment_deviation": 0.0,
        "spline_length": 178.45662520003725,
        "min_radius": 1.5,
        "max_radius": 51.71465560318106,
        "tolerance": 0.01,
        "strategy": "fewest-arcs",
        "max_deviation_segment": 0,
        "t_at_max_deviation": 0.0,
        "curve_length": 178.45662520003728,
        "toolpath_count": 2,
        "max_deviation_toolpath": 0,
    },
    "units": "mm",
    "document": {
        "units": "mm",
        "elements_in": 2,
        "elements_read": 2,
        "elements_skipped": 0,
        "warnings": [],
    },
    "budget": {
        "tolerance": 0.01,
        "curve_approximation": 0.0,
        "snap_move": 0.0,
        "join_gap": 0.0,
        "fit": 0.01,
    },
    "join": {"tolerance": 0.001, "joins": 0},
    "rapids": {"before": 39.644062761670135, "after": 39.644062761670135},
    "offset": {
        "distance": 1.5,
        "side": "outside",
        "contours_in": 2,
        "paths_out": 2,
        "origin": [0, 1],
        "source_max_deviation": 0.00997237617564848,
        "notes": [],
    },
    "gcode": None,
}
HEALTH_ANSWER: dict[str, Any] = {"status": "ok"}

# -- as the document shows them ------------------------------------------------------------

_SHORTENED = f"Each arc spline's first {SHOWN_SEGMENTS} segments; the statistics of all."


def _example(summary: str, value: Any, description: str | None = None) -> dict[str, Any]:
    """An OpenAPI Example Object."""
    example = {"summary": summary, "value": value}
    if description is not None:
        example["description"] = description
    return example


def _batch_answer(ok: dict[str, Any], error: dict[str, Any]) -> dict[str, Any]:
    return {"results": [{"status": "ok", "result": ok}, {"status": "error", "error": error}]}


SPIRAL_REQUESTS = {
    "paper": _example("The paper's example (Table 1: 12 arcs)", PAPER_EXAMPLE),
    "program": _example("The same, answered by its G-code program alone", SPIRAL_PROGRAM_REQUEST),
}
SPIRAL_ANSWERS = {"paper": _example("The paper's 12 arcs", SPIRAL_ANSWER, _SHORTENED)}
SPIRAL_PROGRAMS = {"program": _example("The paper's example as a program", SPIRAL_PROGRAM)}
SPIRAL_BATCH_REQUESTS = {
    "two": _example(
        "The paper's example, and control points not of its form",
        {"jobs": [PAPER_EXAMPLE, SPIRAL_NOT_OF_THE_FORM]},
    )
}
SPIRAL_BATCH_ANSWERS = {
    "two": _example(
        "The paper's 12 arcs, and the second job's refusal",
        _batch_answer(SPIRAL_ANSWER, SPIRAL_NOT_OF_THE_FORM_PROBLEM),
        _SHORTENED,
    )
}

PATH_REQUESTS = {
    "mixed": _example("A cubic, a line and a half circle, closed", PATH_EXAMPLE),
    "program": _example("The same, answered by its G-code program alone", PATH_PROGRAM_REQUEST),
}
PATH_ANSWERS = {"mixed": _example("One closed subpath", PATH_ANSWER, _SHORTENED)}
PATH_PROGRAMS = {"program": _example("The path as one program", PATH_PROGRAM)}
PATH_BATCH_REQUESTS = {
    "two": _example("A path, and path data cut short", {"jobs": [PATH_EXAMPLE, PATH_CUT_SHORT]})
}
PATH_BATCH_ANSWERS = {
    "two": _example(
        "The path, and the second job's refusal",
        _batch_answer(PATH_ANSWER, PATH_CUT_SHORT_PROBLEM),
        _SHORTENED,
    )
}

DRAWING_REQUESTS = {
    "lens-and-hole": _example("An SVG: a closed lens and a circle, 60 × 40 mm", DRAWING_EXAMPLE),
    "program": _example("The same, answered by a 2.5-D program alone", DRAWING_PROGRAM_REQUEST),
    "offset": _example("The same, offset 1.5 mm outside", DRAWING_OFFSET_REQUEST),
}
DRAWING_ANSWERS = {
    "lens-and-hole": _example("Two toolpaths in cutting order", DRAWING_ANSWER, _SHORTENED),
    "offset": _example(
        "The tool-centre paths, each with its contour's sources, and the offset block",
        DRAWING_OFFSET_ANSWER,
        _SHORTENED,
    ),
}
DRAWING_PROGRAMS = {"program": _example("The drawing as one program", DRAWING_PROGRAM)}

HEALTH_ANSWERS = {"ok": _example("The process answers", HEALTH_ANSWER)}
READY_ANSWERS = {"ready": _example("Two workers, idle", READY_ANSWER)}

#: Each operation's examples: of its JSON body (``request``), and of its 200 answer by media
#: type.
OPERATIONS: dict[str, dict[str, dict[str, Any]]] = {
    "approximate": {
        "request": SPIRAL_REQUESTS,
        "application/json": SPIRAL_ANSWERS,
        "text/x-gcode": SPIRAL_PROGRAMS,
    },
    "approximate_batch": {
        "request": SPIRAL_BATCH_REQUESTS,
        "application/json": SPIRAL_BATCH_ANSWERS,
    },
    "approximate_path": {
        "request": PATH_REQUESTS,
        "application/json": PATH_ANSWERS,
        "text/x-gcode": PATH_PROGRAMS,
    },
    "approximate_paths_batch": {
        "request": PATH_BATCH_REQUESTS,
        "application/json": PATH_BATCH_ANSWERS,
    },
    "approximate_drawing": {
        "request": DRAWING_REQUESTS,
        "application/json": DRAWING_ANSWERS,
        "text/x-gcode": DRAWING_PROGRAMS,
    },
    "preview": {"request": SPIRAL_REQUESTS},
    "preview_path": {"request": PATH_REQUESTS},
    "preview_drawing": {"request": DRAWING_REQUESTS},
    "healthz": {"application/json": HEALTH_ANSWERS},
    "readyz": {"application/json": READY_ANSWERS},
}
