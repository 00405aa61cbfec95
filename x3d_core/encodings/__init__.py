"""The three encodings: the XML, ClassicVRML and JSON loaders over one builder (DEF/USE, PROTO), the
XML and ClassicVRML writers, and load(), a file into a validated scene."""
