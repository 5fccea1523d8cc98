// placeholder, replaced while the library is being written
