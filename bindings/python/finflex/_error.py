"""finflex.Error: every error the FinFlex library reports, as a Python exception."""


class Error(Exception):
    """An error of the FinFlex library.

    str(error) is the library's message, naming the field and its value. ``code`` is
    its kind: "invalid_argument", "out_of_range", "invalid_mesh", "io", "format",
    "device" or "opencl". ``field`` is the input at fault, e.g. "m[3]", "parameters",
    "path".
    """

    code: str = ""
    field: str = ""

    def __init__(self, message: str, code: str = "", field: str = "") -> None:
        super().__init__(message)
        self.code = code
        self.field = field
