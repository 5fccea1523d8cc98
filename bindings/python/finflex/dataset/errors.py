"""The dataset generator's errors: bad input (exit status 2, nothing written) and a
run that could not finish (exit status 1, the complete shards kept)."""


class DatasetError(ValueError):
    """Bad input: `field` names the option or configuration field at fault and the
    message says what is wrong with its value."""

    def __init__(self, field: str, message: str):
        super().__init__(message)
        self.field = field


class ShardFailed(RuntimeError):
    """A shard that failed every attempt; the message holds its last error."""

    def __init__(self, index: int, message: str):
        super().__init__(f"shard {index}: {message}")
        self.index = index
