"""A client of dem-server, the DEM simulation service: submit jobs and studies, follow them,
fetch their results and files, and stream their live frames. Standard library only."""

from .client import API, Client
from .errors import ApiError, DemError, ProtocolError, SpecFileError
from .frames import ForceChain, Frame, WallShape, decode_frame
from .inline import inline_files
from .live import FrameStream
from .models import FINAL_STATES, Artifact, Job, Study, StudyRun

__version__ = "0.2.0"

__all__ = [
    "API",
    "ApiError",
    "Artifact",
    "Client",
    "DemError",
    "FINAL_STATES",
    "ForceChain",
    "Frame",
    "FrameStream",
    "Job",
    "ProtocolError",
    "SpecFileError",
    "Study",
    "StudyRun",
    "WallShape",
    "decode_frame",
    "inline_files",
]
