"""FaceSocial: face detection, skin filtering, normalisation and embedded-HMM recognition
for social robots.

Images are numpy arrays: uint8 (H, W) grey or (H, W, 3) BGR, as OpenCV reads them; normalised
faces are float32 (H, W). Boxes are (x, y, width, height) tuples. Caller mistakes raise
ValueError; file problems raise facesocial.FileError (an OSError) or its subclass
facesocial.ModelFormatError. Heavy calls release the GIL, so threads run them in parallel.
"""

from ._facesocial import *  # noqa: F401,F403
from ._facesocial import __version__  # noqa: F401
