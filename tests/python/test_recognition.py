"""A small ORL bank from Python: training, recognition, ranking, the unknown rule, save / load,
the OpenCV peers, and the front end on real photos."""

import numpy as np
import pytest

import facesocial as fs

PEOPLE = 12


@pytest.fixture(scope="module")
def bank(orl):
    b = fs.ClassifierBank(fs.ClassifierBankParams(normalizer=fs.NormalizerParams.cropped()))
    for name, faces in zip(orl.names[:PEOPLE], orl.faces[:PEOPLE]):
        b.add_faces(name, faces[:5])
    assert sorted(b.stale) == sorted(orl.names[:PEOPLE])
    assert sorted(b.train()) == sorted(orl.names[:PEOPLE])
    return b


def test_small_orl_bank_recognises_held_out_faces(bank, orl):
    correct = 0
    for p in range(PEOPLE):
        for face in orl.faces[p][5:]:
            correct += bank.decide(face).name == orl.names[p]
    assert correct / (PEOPLE * 5) >= 0.95
    assert bank.stale == [] and all(bank.is_trained(n) for n in orl.names[:PEOPLE])


def test_scores_ranking_and_decision_agree(bank, orl):
    face = orl.faces[4][7]
    scores = bank.scores(face)
    assert scores.names == bank.trained_people and scores.scores.dtype == np.float64
    assert scores.scores.shape == (PEOPLE,) and np.isfinite(scores.scores).all()
    ranked = bank.rank(face, top_k=3)
    assert [c.name for c in ranked] == [scores.names[i] for i in np.argsort(-scores.scores)[:3]]
    decision = bank.decide(face)
    assert decision.known and decision.name == orl.names[4] == ranked[0].name
    assert decision.margin == pytest.approx(ranked[0].score - ranked[1].score)
    assert decision.variance == pytest.approx(float(np.var(scores.scores)))
    again = bank.decide_scores(fs.BankScores(scores.names, list(scores.scores)))
    assert again.name == decision.name


def test_unknown_rule_turns_strangers_away(bank, orl):
    bank.unknown_rule = fs.UnknownRule(min_margin=0.45)
    try:
        strangers = sum(not bank.decide(f).known for f in orl.faces[30][:10])
        known = sum(bank.decide(f).known for f in orl.faces[0][5:])
    finally:
        bank.unknown_rule = fs.UnknownRule()
    assert strangers >= 6 and known >= 3


def test_save_and_load_give_identical_scores(bank, orl, tmp_path):
    bank.save(tmp_path / "bank.fsb")
    loaded = fs.ClassifierBank.load(str(tmp_path / "bank.fsb"))
    assert loaded.people == bank.people and loaded.params == bank.params
    face = orl.faces[2][9]
    assert np.array_equal(loaded.scores(face).scores, bank.scores(face).scores)


def test_one_person_is_retrained_without_touching_the_others(orl):
    b = fs.ClassifierBank(fs.ClassifierBankParams(normalizer=fs.NormalizerParams.cropped()))
    for p in range(3):
        b.add_faces(orl.names[p], orl.faces[p][:5])
    b.train()
    before = b.scores(orl.faces[1][6]).scores
    b.add_faces(orl.names[0], orl.faces[0][5:7])
    assert b.stale == [orl.names[0]]
    assert b.train(orl.names[0]) == [orl.names[0]]
    after = b.scores(orl.faces[1][6]).scores
    assert after[1] == before[1] and after[2] == before[2] and after[0] != before[0]
    b.remove_person(orl.names[2])
    assert orl.names[2] not in b and len(b.scores(orl.faces[1][6])) == 2


@pytest.mark.parametrize("kind", [fs.ClassifierKind.EIGENFACES, fs.ClassifierKind.FISHERFACES, fs.ClassifierKind.LBPH])
def test_opencv_peers_through_the_classifier_interface(orl, kind):
    classifier = fs.FaceClassifier.create(fs.ClassifierParams(kind=kind))
    classifier.train([faces[:5] for faces in orl.faces[:8]])
    assert len(classifier) == 8
    correct = sum(int(np.argmax(classifier.scores(f))) == p for p in range(8) for f in orl.faces[p][5:])
    assert correct / 40 >= 0.8


def test_front_end_finds_and_normalises_a_real_face(data):
    images = fs.list_images(data / "caltech_faces1999_partial" / "images")
    photo = fs.load_image(images[0])
    result = fs.FrontEnd().process(photo)
    assert len(result.faces) == 1
    face = result.faces[0]
    x, y, w, h = face.detection.box
    assert w > 100 and h > 100 and face.detection.pose == fs.FacePose.FRONTAL
    assert 0.2 <= face.skin_fraction <= 1
    assert face.pixels.dtype == np.float32 and face.pixels.shape == (112, 92)
    grey = fs.load_image(images[0], fs.ImageColor.GREY)
    assert fs.FrontEnd().process(grey).skin_filter_skipped
    detector = fs.FaceDetector.combine([fs.FaceDetector.create(), fs.FaceDetector.create(fs.CascadeDetectorParams.profile())])
    assert any(fs.iou(d.box, face.detection.box) > 0.5 for d in detector.detect(photo))
    skin = fs.SkinFilter()
    mask = skin.skin_mask(photo)
    assert mask.shape == photo.shape[:2] and set(np.unique(mask)) <= {0, 255}
    assert skin.skin_fraction(photo, face.detection.box) == pytest.approx(face.skin_fraction)
