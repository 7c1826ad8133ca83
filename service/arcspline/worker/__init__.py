"""The worker processes: the pool that runs jobs, and the jobs themselves."""
