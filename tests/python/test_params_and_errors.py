"""Params objects: attributes, keyword construction, validation, repr; library errors as Python
exceptions."""

import pickle

import numpy as np
import pytest

import facesocial as fs


def test_params_have_visible_defaults_and_keyword_construction():
    p = fs.EhmmParams()
    assert p.states == [3, 6, 6, 6, 3] and p.mixtures == 3 and p.observations.block_size == 12
    q = fs.EhmmParams(mixtures=2, states=[3, 5, 3])
    assert q.mixtures == 2 and q.states == [3, 5, 3]
    q.observations.block_step = 3  # nested params are changed in place
    assert q.observations.block_step == 3
    assert "mixtures=2" in repr(q) and "block_step=3" in repr(q)
    assert fs.EhmmParams() == fs.EhmmParams() and q != fs.EhmmParams()
    assert pickle.loads(pickle.dumps(q)) == q


def test_invalid_params_raise_value_error_naming_the_field():
    with pytest.raises(ValueError, match="mixtures"):
        fs.EhmmParams(mixtures=0)
    p = fs.EhmmParams()
    p.states = [1] * 40  # more super-states than block rows
    with pytest.raises(ValueError, match="super-states"):
        p.validate()
    with pytest.raises(ValueError, match="min_skin_fraction"):
        fs.SkinFilterParams(min_skin_fraction=2.0)
    skin = fs.SkinFilterParams()
    skin.min_skin_fraction = 2.0  # attributes are not checked one by one; the user is
    with pytest.raises(ValueError, match="min_skin_fraction"):
        fs.SkinFilter(skin)
    with pytest.raises(TypeError, match="unknown field 'mixture'"):
        fs.EhmmParams(mixture=2)
    with pytest.raises(ValueError, match="min_margin"):
        fs.UnknownRule(min_margin=-1)
    with pytest.raises(ValueError):
        fs.classifier_kind("svm")


def test_file_errors_are_oserrors_with_the_path(tmp_path):
    with pytest.raises(fs.FileError) as info:
        fs.load_image(tmp_path / "missing.jpg")
    assert isinstance(info.value, OSError)
    assert info.value.path.endswith("missing.jpg")
    (tmp_path / "not_an_image.jpg").write_text("hello")
    with pytest.raises(OSError, match="not_an_image"):
        fs.load_image(tmp_path / "not_an_image.jpg")
    with pytest.raises(fs.FileError):
        fs.list_images(tmp_path / "no_folder")


def test_damaged_bank_files_raise_model_format_error_and_keep_the_old_file(orl, tmp_path):
    bank = fs.ClassifierBank(fs.ClassifierBankParams(normalizer=fs.NormalizerParams.cropped()))
    bank.add_faces("ann", orl.faces[0][:3])
    bank.train()
    path = tmp_path / "bank.fsb"
    bank.save(path)
    data = path.read_bytes()
    (tmp_path / "truncated.fsb").write_bytes(data[: len(data) // 2])
    with pytest.raises(fs.ModelFormatError, match="truncated"):
        fs.ClassifierBank.load(tmp_path / "truncated.fsb")
    flipped = bytearray(data)
    flipped[len(data) // 2] ^= 0x10
    (tmp_path / "flipped.fsb").write_bytes(bytes(flipped))
    with pytest.raises(fs.ModelFormatError, match="checksum"):
        fs.ClassifierBank.load(tmp_path / "flipped.fsb")
    (tmp_path / "foreign.fsb").write_bytes(b"P5\n92 112\n255\n" + bytes(200))
    with pytest.raises(fs.FileError, match="magic"):
        fs.ClassifierBank.load(tmp_path / "foreign.fsb")
    with pytest.raises(fs.FileError):
        bank.save(tmp_path / "no_folder" / "bank.fsb")
    assert path.read_bytes() == data


def test_bank_caller_mistakes_raise_value_error(orl):
    bank = fs.ClassifierBank(fs.ClassifierBankParams(normalizer=fs.NormalizerParams.cropped()))
    with pytest.raises(ValueError, match="bob"):
        bank.train("bob")
    bank.add_person("ann")
    with pytest.raises(ValueError):
        bank.add_person("ann")
    with pytest.raises(ValueError):
        bank.add_person("")
    assert len(bank.scores(orl.faces[0][0])) == 0
    assert not bank.decide(orl.faces[0][0]).known
