"""Message definitions (``<package>__<Type>.msg``) registered by ``loaders.typestore``."""
