"""Measurements of meshes and weaves: counts, angles, fractal dimension, level images."""
