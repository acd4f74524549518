"""Shared fixtures: the data root and ORL faces loaded once per session."""

import os
import pathlib

import pytest

import facesocial as fs


@pytest.fixture(scope="session")
def data() -> pathlib.Path:
    root = os.environ.get("FACESOCIAL_DATA")
    if not root or not pathlib.Path(root).is_dir():
        pytest.fail("FACESOCIAL_DATA must name the folder of the face sets (see datasets/README)")
    return pathlib.Path(root)


@pytest.fixture(scope="session")
def orl(data) -> fs.FaceSet:
    return fs.load_cropped_faces(data / "orl")
