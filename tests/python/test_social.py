"""Social tagging from Python: tags to faces on a real group photo, friend-biased tagging with
real ORL scores, suggestions, training-set selection and background retraining."""

import numpy as np
import pytest

import facesocial as fs


def test_tags_resolve_to_the_nearest_frontal_face_and_profiles_refuse(data):
    photo = fs.load_image(data / "dlib_faces" / "2008_002470.jpg")
    faces = [f.detection for f in fs.FrontEnd(fs.FrontEndParams(normalize=False)).process(photo).faces]
    assert len(faces) >= 2
    x, y, w, h = faces[0].box
    tags = [fs.PhotoTag("ann", (x + w / 2 + 3, y + h / 2 - 2))]
    size = (photo.shape[1], photo.shape[0])
    result = fs.resolve_tags(faces, tags, size)
    assert result[0].outcome == fs.TagOutcome.RESOLVED and result[0].face == 0
    faces[0].pose = fs.FacePose.PROFILE_RIGHT
    refused = fs.resolve_tags(faces, tags, size)
    assert refused[0].outcome == fs.TagOutcome.NEAREST_IS_PROFILE and "profile" in refused[0].reason
    with pytest.raises(ValueError, match="inside the"):
        fs.resolve_tags(faces, [fs.PhotoTag("ann", (size[0] + 5, 5))], size)
    with pytest.raises(ValueError, match="twice"):
        fs.resolve_tags(faces, [fs.PhotoTag("ann", (5, 5)), fs.PhotoTag("ann", (9, 9))], size)


def test_friend_prior_on_real_scores(orl):
    bank = fs.ClassifierBank(fs.ClassifierBankParams(normalizer=fs.NormalizerParams.cropped()))
    for name, faces in zip(orl.names[:6], orl.faces[:6]):
        bank.add_faces(name, faces[:3])
    bank.train()
    photo = [bank.scores(orl.faces[p][8]) for p in (0, 1, 2)]
    alone = fs.tag_faces(photo)
    assert sorted(t.order for t in alone) == [0, 1, 2]
    assert len({t.name for t in alone if t.known}) == sum(t.known for t in alone)
    graph = fs.InMemorySocialGraph([(orl.names[0], orl.names[1]), (orl.names[1], orl.names[2])])
    biased = fs.tag_faces(photo, graph, fs.FriendTaggingParams(friend_bonus=0.3))
    assert [t.name for t in biased] == orl.names[:3]
    assert any(t.bonus > 0 for t in biased)
    history = [[orl.names[0], orl.names[1]], [orl.names[1], orl.names[2]], [orl.names[3], orl.names[4]]]
    assert fs.friend_lift(history, graph) > 1
    assert fs.calibrated_friend_bonus(history, graph) > 0
    suggestions = fs.suggest_friendships(history + [[orl.names[3], orl.names[4]]], graph, 2)
    assert [(s.a, s.b, s.photos) for s in suggestions] == [(orl.names[3], orl.names[4], 2)]


def test_training_policy_and_background_trainer(orl):
    samples = [fs.TrainingSample(f, fs.SampleSource.CAMERA, float(i), "s") for i, f in enumerate(orl.faces[2])]
    report = fs.select_training_samples(samples, fs.TrainingPolicy(max_size=4, prefer_recent=False))
    assert report.kept == [0, 3, 6, 9] and len(report.capped) == 6
    assert samples[0].face.dtype == np.float32
    bank = fs.ClassifierBank(fs.ClassifierBankParams(normalizer=fs.NormalizerParams.cropped()))
    bank.add_faces(orl.names[2], orl.faces[2][:3])
    bank.add_faces(orl.names[3], orl.faces[3][:3])
    bank.train()
    bank.add_faces(orl.names[2], fs.augment_faces(orl.faces[2][:5], 40, seed=1))
    trainer = fs.BackgroundTrainer(bank)
    trainer.request(orl.names[2])
    trainer.wait_idle()
    assert trainer.trained == 1 and bank.is_trained(orl.names[2])
    with pytest.raises(ValueError):
        fs.TrainingPolicy(prune_sigma=-1)


def test_bank_keeps_provenance_and_applies_its_policy(orl, tmp_path):
    params = fs.ClassifierBankParams(normalizer=fs.NormalizerParams.cropped(), training=fs.TrainingPolicy(max_size=2))
    bank = fs.ClassifierBank(params)
    bank.add_samples(orl.names[0], [fs.TrainingSample(f, fs.SampleSource.SOCIAL_PHOTO, 10.0 * i, "party")
                                    for i, f in enumerate(orl.faces[0][:4])])
    bank.train()
    assert bank.selection(orl.names[0]).kept == [2, 3]
    bank.save(tmp_path / "b.fsb")
    back = fs.ClassifierBank.load(tmp_path / "b.fsb")
    assert back.params.training.max_size == 2
    s = back.samples(orl.names[0])
    assert [x.session for x in s] == ["party"] * 4 and s[1].source == fs.SampleSource.SOCIAL_PHOTO
