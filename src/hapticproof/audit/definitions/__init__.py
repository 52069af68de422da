"""A paper read as its definitions: names bound by displays, identities and conditions decided on them."""
