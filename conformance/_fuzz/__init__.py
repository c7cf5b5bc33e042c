"""Differential fuzzing: strategies, the lockstep state machine, campaigns, findings as files.

Two kinds of campaign share seeds, budgets and findings (``campaign``):

- SceneGraph command sequences, in lockstep on two backends (``strategies``,
  ``sequences``, ``lockstep``);
- random models, as scenario cases run by the corpus runner (``models``: the
  public kinematic-tree strategies and their URDF/SDFormat rendering;
  ``model_campaign``: ``fuzz --models``).
"""
