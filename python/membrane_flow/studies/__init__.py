"""The studies behind the pages of docs/: mesh convergence, neck resolution, time-step accuracy,
experiment 7.1 over seeds and meshes, and the axisymmetric reference shapes of the vesicles."""
