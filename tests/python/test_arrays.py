"""numpy <-> library round trips for every supported array type, and clear errors for the rest."""

import numpy as np
import pytest

import facesocial as fs


def test_images_load_and_save_as_uint8_grey_and_bgr(data, tmp_path):
    grey = fs.load_image(data / "orl" / "s1" / "1.pgm", fs.ImageColor.GREY)
    assert grey.dtype == np.uint8 and grey.shape == (112, 92)
    bgr = fs.load_image(data / "orl" / "s1" / "1.pgm")
    assert bgr.dtype == np.uint8 and bgr.shape == (112, 92, 3)
    assert np.array_equal(bgr[:, :, 0], grey) and np.array_equal(bgr[:, :, 2], grey)
    for name, image in [("grey.png", grey), ("bgr.png", bgr)]:
        fs.save_image(tmp_path / name, image)
        back = fs.load_image(tmp_path / name, fs.ImageColor.ANY)
        assert back.dtype == np.uint8 and np.array_equal(back, image)


def test_faces_accept_uint8_and_float32_and_give_the_same_observations(data):
    face = fs.load_image(data / "orl" / "s3" / "2.pgm", fs.ImageColor.GREY)
    from_u8 = fs.extract_observations(face)
    from_f32 = fs.extract_observations(face.astype(np.float32))
    assert from_u8.dtype == np.float32
    params = fs.ObservationParams()
    columns, rows = params.grid
    assert from_u8.shape == (rows * columns, params.dimension)
    np.testing.assert_allclose(from_u8, from_f32, rtol=1e-5, atol=1e-4)


def test_normalised_faces_are_float32_with_zero_mean_and_unit_deviation(data):
    image = fs.load_image(data / "orl" / "s7" / "4.pgm")
    pixels, mask = fs.FaceNormalizer(fs.NormalizerParams.cropped()).normalize(image)
    assert pixels.dtype == np.float32 and pixels.shape == (112, 92)
    assert mask.dtype == np.uint8 and mask.shape == (112, 92)
    assert abs(float(pixels.mean())) < 1e-3 and abs(float(pixels.std()) - 1) < 1e-2
    masked, mask = fs.FaceNormalizer().normalize(image, (10, 10, 60, 80))
    assert (masked[mask == 0] == 0).all() and mask.min() == 0 and mask.max() == 255
    picture = fs.FaceNormalizer.to_8bit(masked, mask)
    assert picture.dtype == np.uint8 and picture.shape == (112, 92)


def test_augmented_faces_keep_dtype_and_shape(orl):
    for faces in (orl.faces[0][:2], [(f * 40 + 128).clip(0, 255).astype(np.uint8) for f in orl.faces[0][:2]]):
        out = fs.augment_faces(faces, 5, seed=3)
        assert len(out) == 5
        assert all(f.dtype == faces[0].dtype and f.shape == faces[0].shape for f in out)
        assert np.array_equal(out[0], faces[0]) and not np.array_equal(out[2], faces[0])
        again = fs.augment_faces(faces, 5, seed=3)
        assert all(np.array_equal(a, b) for a, b in zip(out, again))


def test_arrays_are_not_kept_by_reference(orl):
    bank = fs.ClassifierBank(fs.ClassifierBankParams(normalizer=fs.NormalizerParams.cropped()))
    face = orl.faces[0][0].copy()
    bank.add_faces("ann", [face])
    face[:] = 0
    stored = bank.faces("ann")[0]
    assert np.array_equal(stored, orl.faces[0][0])
    stored[:] = 5  # a copy too: the bank is unchanged
    assert np.array_equal(bank.faces("ann")[0], orl.faces[0][0])


BAD_IMAGES = [
    (np.zeros((20, 20), np.float64), "dtype float64"),
    (np.zeros((20, 20), np.int16), "dtype int16"),
    (np.zeros(400, np.uint8), "shape (400,)"),
    (np.zeros((20, 20, 4), np.uint8), "shape (20, 20, 4)"),
    (np.zeros((20, 20, 2), np.uint8), "shape (20, 20, 2)"),
    (np.zeros((0, 20), np.uint8), "non-empty"),
    (np.zeros((40, 40), np.uint8)[:, ::2], "not C-contiguous"),
    (np.asfortranarray(np.zeros((20, 30), np.uint8)), "not C-contiguous"),
]


@pytest.mark.parametrize("array,message", BAD_IMAGES)
def test_bad_images_raise_value_error_saying_what_came(array, message):
    with pytest.raises(ValueError, match="FaceDetector.detect: expected") as info:
        fs.FaceDetector.default().detect(array)
    assert message in str(info.value)


def test_bad_faces_raise_value_error(orl):
    bank = fs.ClassifierBank(fs.ClassifierBankParams(normalizer=fs.NormalizerParams.cropped()))
    bank.add_faces("ann", orl.faces[0][:2])
    bank.train()
    with pytest.raises(ValueError, match="shape \\(112, 92, 3\\)"):
        bank.scores(np.zeros((112, 92, 3), np.uint8))  # colour is not a normalised face
    with pytest.raises(ValueError, match="float64"):
        bank.scores(orl.faces[0][0].astype(np.float64))
    with pytest.raises(ValueError, match="ClassifierBank::scores"):
        bank.scores(np.zeros((50, 50), np.float32))  # wrong size: the library's own check
    with pytest.raises(ValueError, match=r"add_faces\[1\]"):
        bank.add_faces("ann", [orl.faces[0][0], orl.faces[0][0].T])
    with pytest.raises(TypeError):
        bank.scores("not an array")


def test_boxes_and_sizes_are_tuples():
    detection = fs.Detection((1, 2, 30, 40), fs.FacePose.PROFILE_LEFT, 0.5)
    assert detection.box == (1, 2, 30, 40) and detection.is_profile
    assert fs.iou((0, 0, 10, 10), (5, 0, 10, 10)) == pytest.approx(1 / 3)
    with pytest.raises(ValueError, match="expected a box"):
        fs.Detection((1, 2, 3))
    params = fs.NormalizerParams(output_size=(46, 56))
    assert params.output_size == (46, 56)
    with pytest.raises(ValueError, match="expected a size"):
        params.output_size = (1, 2, 3)
