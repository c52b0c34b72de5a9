#!/usr/bin/env python3
"""Reads VTK XML files with VTK's own readers (Debian's python3-vtk9, the readers ParaView uses)
and prints what they hold as JSON, one object per file given: its point and cell counts, its
field data, and for each array its components, tuples, range and first tuple. A .pvd series is
read as XML (its reader is ParaView's, not VTK's): the times and files it lists."""
import json
import sys
import xml.etree.ElementTree as ET

import vtk


def arrays(data):
    out = {}
    for k in range(data.GetNumberOfArrays()):
        a = data.GetAbstractArray(k)
        entry = {"components": a.GetNumberOfComponents(), "tuples": a.GetNumberOfTuples()}
        if isinstance(a, vtk.vtkDataArray) and a.GetNumberOfTuples() > 0:
            entry["range"] = list(a.GetRange(-1 if a.GetNumberOfComponents() > 1 else 0))
            entry["first"] = list(a.GetTuple(0))
            entry["all"] = [list(a.GetTuple(i)) for i in range(min(a.GetNumberOfTuples(), 200))]
        out[a.GetName()] = entry
    return out


def read(path):
    if path.endswith(".pvd"):
        root = ET.parse(path).getroot()
        return {"series": [{"time": float(d.get("timestep")), "file": d.get("file")} for d in root.iter("DataSet")]}
    reader = vtk.vtkXMLUnstructuredGridReader() if path.endswith(".vtu") else vtk.vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    if reader.GetErrorCode() != 0:
        return {"error": vtk.vtkErrorCode.GetStringFromErrorCode(reader.GetErrorCode())}
    d = reader.GetOutput()
    points = d.GetPoints()
    return {
        "points": d.GetNumberOfPoints(),
        "cells": d.GetNumberOfCells(),
        "cellTypes": sorted({d.GetCellType(i) for i in range(d.GetNumberOfCells())}),
        "coordinates": [list(points.GetPoint(i)) for i in range(min(d.GetNumberOfPoints(), 200))] if points else [],
        "pointData": arrays(d.GetPointData()),
        "cellData": arrays(d.GetCellData()),
        "fieldData": arrays(d.GetFieldData()),
    }


if __name__ == "__main__":
    print(json.dumps({p: read(p) for p in sys.argv[1:]}))
