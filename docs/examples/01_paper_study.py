"""The paper's study: Table 4, the quadratic of Eq. 19 and the optimum

Su, Zhang & Yang (2023) ran a 27-run Box–Behnken design on four factors of the linear rolling
guide (leaf thickness, stroke, velocity, acceleration) and fitted a quadratic to the temperature
change rate κ [°C/min] (their Eq. 19 and Table 5). The toolkit fits the same model from the
embedded Table 4 and finds the setting of least heating inside the factor box.
"""
import rsm_lrg

table4 = rsm_lrg.load_table4()
print(table4.head())

result = rsm_lrg.fit(table4, "tcr_c_per_min", model="quadratic")
print(result.summary())

best = result.optimize(goal="minimize")
print(best.summary())
