"""Negative typing case: a misspelled modality is a type error, as a dict key and as an enum member; so are an
anti-aliasing method given as a number and one spear does not have, an exposure method given as a string, a
rect light's size given as a string and a size property it does not have, a fractional anisotropy and a
mip bias given as a word."""

# pyright: standard
# (negative cases are checked as most pyright and Pylance users run it; strict reports more)

from __future__ import annotations

import spear


def misuse(camera: spear.UCameraSensorComponent, panel: spear.URectLightComponent) -> None:
    px = camera.read_pixels()
    px["dept"]  # E: TypedDict "FCameraPixels" has no key "dept"  [typeddict-item]  # P: reportGeneralTypeIssues: Could not access item in TypedDict / "dept" is not a defined key in "FCameraPixels"
    camera.Modalities = [spear.ECameraModality.Dept]  # E: "Type[ECameraModality]" has no attribute "Dept"  [attr-defined]  # P: reportAttributeAccessIssue: Cannot access attribute "Dept" for class "type[ECameraModality]" / Attribute "Dept" is unknown
    camera.Modalities = ["depth"]  # E: List item 0 has incompatible type "str"; expected "ECameraModality"  [list-item]  # P: reportAttributeAccessIssue: Cannot assign to attribute "Modalities" for class "UCameraSensorComponent" / "Literal['depth']" is not assignable to "ECameraModality"
    camera.CameraSensor  # E: "UCameraSensorComponent" has no attribute "CameraSensor"  [attr-defined]  # P: reportAttributeAccessIssue: Cannot access attribute "CameraSensor" for class "UCameraSensorComponent" / Attribute "CameraSensor" is unknown
    camera.AntiAliasingMethod = 3  # E: Incompatible types in assignment (expression has type "int", variable has type "EAntiAliasingMethod")  [assignment]  # P: reportAttributeAccessIssue: Cannot assign to attribute "AntiAliasingMethod" for class "UCameraSensorComponent" / "Literal[3]" is not assignable to "EAntiAliasingMethod"
    camera.AntiAliasingMethod = spear.EAntiAliasingMethod.AAM_TSR  # E: "Type[EAntiAliasingMethod]" has no attribute "AAM_TSR"  [attr-defined]  # P: reportAttributeAccessIssue: Cannot access attribute "AAM_TSR" for class "type[EAntiAliasingMethod]" / Attribute "AAM_TSR" is unknown
    camera.AutoExposureMethod = "Histogram"  # E: Incompatible types in assignment (expression has type "str", variable has type "EAutoExposureMethod")  [assignment]  # P: reportAttributeAccessIssue: Cannot assign to attribute "AutoExposureMethod" for class "UCameraSensorComponent" / "Literal['Histogram']" is not assignable to "EAutoExposureMethod"
    camera.ResetAutoExposure(Instant=True)  # E: Unexpected keyword argument "Instant" for "ResetAutoExposure" of "UCameraSensorComponent"  [call-arg]  # P: reportCallIssue: No parameter named "Instant"
    panel.SetSourceWidth(NewWidth="1.2")  # E: Argument "NewWidth" to "SetSourceWidth" of "URectLightComponent" has incompatible type "str"; expected "float"  [arg-type]  # P: reportArgumentType: Argument of type "Literal['1.2']" cannot be assigned to parameter "NewWidth" of type "float" in function "SetSourceWidth" / "Literal['1.2']" is not assignable to "float"
    panel.SourceLength = 1.0  # E: "URectLightComponent" has no attribute "SourceLength"  [attr-defined]  # P: reportAttributeAccessIssue: Cannot assign to attribute "SourceLength" for class "URectLightComponent" / Attribute "SourceLength" is unknown
    camera.MaxAnisotropy = 2.5  # E: Incompatible types in assignment (expression has type "float", variable has type "int")  [assignment]  # P: reportAttributeAccessIssue: Cannot assign to attribute "MaxAnisotropy" for class "UCameraSensorComponent" / "float" is not assignable to "int"
    camera.MipMapLODBias = "sharp"  # E: Incompatible types in assignment (expression has type "str", variable has type "float")  [assignment]  # P: reportAttributeAccessIssue: Cannot assign to attribute "MipMapLODBias" for class "UCameraSensorComponent" / "Literal['sharp']" is not assignable to "float"
