// Placeholder on branch cmake-package; the library API branch provides this file.
