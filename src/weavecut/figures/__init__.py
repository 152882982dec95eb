"""The paper's figures and the gallery that names them."""
