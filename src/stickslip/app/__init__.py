"""Private: the Streamlit web app (``stickslip app``). Its contract is the app, not this code."""
