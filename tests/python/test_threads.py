"""Threads calling the library in parallel: the GIL is released during heavy work, results do
not depend on what the other threads do, and retraining while scoring is safe."""

import threading
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np

import facesocial as fs


def make_bank(orl, people=8):
    b = fs.ClassifierBank(fs.ClassifierBankParams(normalizer=fs.NormalizerParams.cropped()))
    for name, faces in zip(orl.names[:people], orl.faces[:people]):
        b.add_faces(name, faces[:5])
    b.train()
    return b


def test_parallel_scoring_matches_serial_scoring(orl):
    bank = make_bank(orl)
    probes = [f for faces in orl.faces[:8] for f in faces[5:]]
    serial = [bank.scores(f).scores for f in probes]
    with ThreadPoolExecutor(max_workers=4) as pool:
        parallel = list(pool.map(lambda f: bank.scores(f).scores, probes))
    assert all(np.array_equal(a, b) for a, b in zip(serial, parallel))


def test_the_gil_is_released_during_heavy_calls(orl):
    # A Python thread keeps counting while the main thread is inside one long C++ call (training
    # 40 people, about 0.1 s). Had the call kept the GIL, the counter could not move until it
    # returned.
    bank = fs.ClassifierBank(fs.ClassifierBankParams(normalizer=fs.NormalizerParams.cropped()))
    for name, faces in zip(orl.names, orl.faces):
        bank.add_faces(name, faces[:5])
    ticks = 0
    done = threading.Event()

    def tick():
        nonlocal ticks
        while not done.is_set():
            ticks += 1
            time.sleep(0.0005)

    ticker = threading.Thread(target=tick)
    ticker.start()
    time.sleep(0.01)
    before = ticks
    bank.train()
    during = ticks - before
    done.set()
    ticker.join()
    assert len(bank.trained_people) == 40
    assert during >= 5


def test_scoring_while_one_person_is_retrained(orl):
    bank = make_bank(orl)
    probe = orl.faces[3][8]
    reference = bank.scores(probe).scores
    stop = threading.Event()
    errors = []

    def score():
        while not stop.is_set():
            s = bank.scores(probe)
            if len(s) != 8 or not np.isfinite(s.scores).all() or s.scores[3] != reference[3]:
                errors.append(s)

    workers = [threading.Thread(target=score) for _ in range(3)]
    for w in workers:
        w.start()
    for round_ in range(3):
        bank.add_faces(orl.names[0], [orl.faces[0][5 + round_]])
        bank.train(orl.names[0])
    stop.set()
    for w in workers:
        w.join()
    assert errors == []
    assert bank.face_count(orl.names[0]) == 8 and bank.stale == []
